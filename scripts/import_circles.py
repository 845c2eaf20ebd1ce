#!/usr/bin/env python3
"""Import circles between the files of each crate (a file = a module; `crate::`, `super::` and
the crate root's `pub use` re-exports are resolved to files; test modules are left out).
Usage: python3 scripts/import_circles.py crates/*   (exit code 1 when a crate has a circle)."""
import os,re,sys
from collections import defaultdict
def modpath(root,f):
    rel=os.path.relpath(f,root)[:-3].split('/')
    if rel[-1]=='mod': rel=rel[:-1]
    if rel==['lib'] or rel==['main']: return ()
    return tuple(rel)
def analyse(crate):
    root=os.path.join(crate,'src')
    files={}
    for d,_,fs in os.walk(root):
        for f in fs:
            if f.endswith('.rs'): files[modpath(root,os.path.join(d,f))]=os.path.join(d,f)
    # lib re-exports: name -> module
    reexp={}
    lib=files.get(())
    if lib:
        txt=open(lib).read()
        for m in re.finditer(r'pub use ([a-z_:]+)::\{([^}]*)\}',txt):
            for n in re.split(r'[,\s]+',m.group(2)):
                n=n.split(' as ')[-1].strip()
                if n: reexp[n]=tuple(m.group(1).split('::'))
        for m in re.finditer(r'pub use ([a-z_:]+)::(\w+);',txt):
            reexp[m.group(2)]=tuple(m.group(1).split('::'))
    def resolve(path):
        # longest prefix that is a file module
        for k in range(len(path),0,-1):
            if tuple(path[:k]) in files: return tuple(path[:k])
        return None
    g=defaultdict(set)
    for mp,f in files.items():
        if mp==(): continue
        txt=open(f).read()
        txt=re.sub(r'//[^\n]*','',txt)
        # cut tests
        i=txt.find('#[cfg(test)]')
        if i>=0: txt=txt[:i]
        for m in re.finditer(r'crate::((?:\w+::)*\w+)',txt):
            parts=m.group(1).split('::')
            t=resolve(parts)
            if t is None and parts[0] in reexp: t=resolve(list(reexp[parts[0]]))
            if t and t!=mp and not (len(t)<len(mp) and mp[:len(t)]==t): g[mp].add(t)
        for m in re.finditer(r'crate::\{([^}]*)\}',txt):
            for n in re.split(r'[,\s]+',m.group(1)):
                n=n.strip().split('::')[0]
                if not n: continue
                t=resolve([n]) or (resolve(list(reexp[n])) if n in reexp else None)
                if t and t!=mp and not (len(t)<len(mp) and mp[:len(t)]==t): g[mp].add(t)
        for m in re.finditer(r'super::((?:\w+::)*\w+)',txt):
            base=list(mp[:-1]) if not f.endswith('mod.rs') else list(mp[:-1])
            parts=m.group(1).split('::')
            if parts[0]=='super': continue
            t=resolve(base+parts)
            if t and t!=mp and not (len(t)<len(mp) and mp[:len(t)]==t): g[mp].add(t)
    # SCC
    idx={};low={};st=[];on=set();out=[];c=[0]
    sys.setrecursionlimit(10000)
    def sc(v):
        idx[v]=low[v]=c[0];c[0]+=1;st.append(v);on.add(v)
        for w in g.get(v,()):
            if w not in idx: sc(w);low[v]=min(low[v],low[w])
            elif w in on: low[v]=min(low[v],idx[w])
        if low[v]==idx[v]:
            comp=[]
            while True:
                w=st.pop();on.discard(w);comp.append(w)
                if w==v: break
            if len(comp)>1: out.append(comp)
    for v in list(files):
        if v not in idx: sc(v)
    return out
found=False
for crate in sys.argv[1:]:
    comps=analyse(crate)
    found = found or bool(comps)
    print(crate, 'circles:', ['/'.join('::'.join(x) for x in c) for c in comps] or 'none')
sys.exit(1 if found else 0)
