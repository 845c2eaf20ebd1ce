#!/usr/bin/env python3
"""List Rust functions longer than N lines (signature to closing brace) and files longer than M
lines (issue 36: no library function over 150 lines, no file over 700 in the top floors).
Inline test modules (`#[cfg(test)] mod x { ... }`) are left out of the functions; files of
test modules declared elsewhere (`#[cfg(test)] mod tests;`) are listed like any file.
Usage: python3 scripts/long_functions.py [--fn N] [--file M] PATH...   (defaults 150 and 700;
a PATH is a file or a folder searched for .rs files; exit code 1 when something is over), e.g.
python3 scripts/long_functions.py crates/alea-study/src crates/alea-pipeline/src"""
import os, re, sys

FN = re.compile(r'^\s*(pub(\([^)]*\))?\s+)?(const\s+)?(async\s+)?(unsafe\s+)?(extern\s+"[^"]*"\s+)?fn\s+(\w+)')

def strip(line, state):
    """The line without comments and string contents (state carries block comments / strings)."""
    out = []
    i = 0
    while i < len(line):
        c = line[i]
        if state['block']:
            if line.startswith('*/', i):
                state['block'] -= 1; i += 2; continue
            if line.startswith('/*', i):
                state['block'] += 1; i += 2; continue
            i += 1; continue
        if state['str']:
            if c == '\\': i += 2; continue
            if c == '"': state['str'] = False
            i += 1; continue
        if line.startswith('//', i): break
        if line.startswith('/*', i): state['block'] += 1; i += 2; continue
        if c == '"': state['str'] = True; i += 1; continue
        if c == "'":
            m = re.match(r"'(\\.|[^\\'])'", line[i:]) or re.match(r"'\\u\{[0-9a-fA-F]+\}'", line[i:])
            if m: i += len(m.group(0)); continue
        out.append(c); i += 1
    return ''.join(out)

def functions(path):
    lines = open(path, encoding='utf-8').read().split('\n')
    state = {'block': 0, 'str': False}
    code = [strip(l, state) for l in lines]
    res = []
    skip_test = False
    i = 0
    while i < len(lines):
        if re.match(r'\s*#\[cfg\(test\)\]', code[i]):
            j = i + 1
            if j < len(code) and re.match(r'\s*(pub\s+)?mod\s+\w+\s*\{', code[j]):
                depth = 0; k = j
                while k < len(code):
                    depth += code[k].count('{') - code[k].count('}')
                    if depth == 0 and '{' in ''.join(code[j:k+1]): break
                    k += 1
                i = k + 1; continue
        m = FN.match(code[i])
        if m:
            depth = 0; opened = False; k = i
            while k < len(code):
                for ch in code[k]:
                    if ch == '{': depth += 1; opened = True
                    elif ch == '}': depth -= 1
                    elif ch == ';' and not opened and depth == 0: break
                else:
                    if opened and depth == 0: break
                    k += 1; continue
                if not opened: k = -1
                break
            if k >= 0 and opened:
                res.append((m.group(7), i + 1, k - i + 1))
        i += 1
    return res, len(lines) - (1 if lines and lines[-1] == '' else 0)

def main():
    args = sys.argv[1:]
    fn_limit, file_limit = 150, 700
    paths = []
    while args:
        a = args.pop(0)
        if a == '--fn': fn_limit = int(args.pop(0))
        elif a == '--file': file_limit = int(args.pop(0))
        else: paths.append(a)
    files = []
    for p in paths:
        if os.path.isdir(p):
            for d, _, fs in os.walk(p):
                files += [os.path.join(d, f) for f in fs if f.endswith('.rs')]
        else:
            files.append(p)
    over = False
    for f in sorted(files):
        fns, n = functions(f)
        if n > file_limit:
            print(f'{f}: file {n} lines'); over = True
        for name, line, length in fns:
            if length > fn_limit:
                print(f'{f}:{line}: fn {name} {length} lines'); over = True
    sys.exit(1 if over else 0)

main()
