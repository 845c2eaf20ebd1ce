//! The page's style sheet.

pub(super) const CSS: &str = r#"
:root { --ink:#1d2733; --muted:#5b6775; --line:#dde3ea; --band:#f4f6f9; --accent:#0b4f8a;
  --ok:#1e7b34; --bad:#b3261e; --warn-bg:#fff6e0; --warn-line:#e0a100; }
* { box-sizing: border-box; }
body { margin:0; background:#eef1f5; color:var(--ink);
  font: 15px/1.5 "DejaVu Sans", "Segoe UI", Helvetica, Arial, sans-serif; }
main { max-width: 1040px; margin: 0 auto; padding: 0 24px 40px; }
header.top { background: linear-gradient(120deg, #0b3d6b, #0b4f8a 60%, #136fae); color:#fff;
  padding: 28px 0 24px; margin-bottom: 24px; }
header.top .inner { max-width:1040px; margin:0 auto; padding:0 24px; }
header.top h1 { margin:0 0 4px; font-size: 28px; font-weight: 600; letter-spacing: .2px; }
header.top .sub { opacity:.85; font-size:14px; }
.bad { color:#b3261e; }
section { background:#fff; border:1px solid var(--line); border-radius:8px; padding:20px 24px;
  margin: 0 0 20px; box-shadow: 0 1px 2px rgba(20,30,40,.05); }
h2 { font-size: 20px; margin: 0 0 14px; color: var(--accent); font-weight: 600; }
h3 { font-size: 15px; margin: 18px 0 8px; color: var(--muted); text-transform: uppercase;
  letter-spacing: .6px; font-weight: 600; }
dl.meta { display:grid; grid-template-columns: 140px 1fr; gap: 6px 16px; margin:0; }
dl.meta dt { color: var(--muted); }
dl.meta dd { margin:0; }
code { font-family: "DejaVu Sans Mono", Menlo, Consolas, monospace; font-size: 13px;
  background: var(--band); padding: 1px 5px; border-radius: 4px; word-break: break-all; }
.chip { display:inline-block; border:1px solid var(--line); background:var(--band);
  border-radius: 12px; padding: 0 10px; margin: 0 6px 4px 0; font-size: 13px; }
.warn { background: var(--warn-bg); border: 1px solid var(--warn-line);
  border-left: 6px solid var(--warn-line); }
.warn h2 { color: #7a5200; }
.warn ul { margin: 0; padding-left: 20px; }
.ok-note { color: var(--muted); font-size: 14px; }
table { border-collapse: collapse; width: 100%; font-size: 14px; }
th, td { padding: 6px 10px; border-bottom: 1px solid var(--line); text-align: left;
  vertical-align: top; }
th { background: var(--band); font-weight: 600; color: #344252; white-space: nowrap; }
td.n, th.n { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
tr.ref td { font-weight: 600; }
tbody tr:hover td { background: #fafbfd; }
.tables { display:flex; flex-wrap: wrap; gap: 0 28px; }
.tables > div { flex: 1 1 auto; min-width: 230px; }
figure { margin: 16px auto 8px; max-width: 900px; }
figure svg.plot { width: 100%; height: auto; display:block; border:1px solid var(--line);
  border-radius: 6px; background:#fff; }
figcaption { font-size: 13px; color: var(--muted); margin-top: 6px; }
figcaption a { color: var(--accent); }
.badge { display:inline-block; padding: 0 8px; border-radius: 10px; font-size: 12px;
  font-weight: 600; white-space: nowrap; }
.badge.ok { background:#e3f4e7; color: var(--ok); }
.badge.bad { background:#fde8e6; color: var(--bad); }
details > summary { cursor: pointer; font-weight: 600; color: var(--accent); margin-bottom: 8px; }
.scroll { overflow-x: auto; }
.bar { display:inline-block; height: 10px; background: #6a9fd0; border-radius: 2px;
  vertical-align: middle; }
.hint { color: var(--muted); font-size: 13px; margin: -4px 0 6px; }
tr.failed td { background: #fff7f6; }
@media print {
  body { background: #fff; }
  header.top { background: none; color: var(--ink); border-bottom: 2px solid var(--accent); }
  section { box-shadow: none; break-inside: avoid-page; }
  figure { break-inside: avoid; }
}
.glance { display:grid; grid-template-columns: repeat(auto-fit, minmax(230px, 1fr)); gap: 12px;
  margin-top: 18px; }
.card { display:block; text-decoration:none; color:inherit; border:1px solid var(--line);
  border-top: 4px solid var(--accent); border-radius: 6px; padding: 10px 14px; background:#fbfcfe; }
.card .name { color: var(--muted); font-size: 13px; }
.card .big { font-size: 22px; font-weight: 600; font-variant-numeric: tabular-nums; }
.card .pm { font-weight: 400; color: #344252; }
.card .unit { font-size: 14px; font-weight: 400; color: var(--muted); }
.card .pf { font-size: 13px; color: #344252; }
.card .ci, td .ci { color: var(--muted); }
nav.toc { margin-top: 10px; font-size: 13px; }
nav.toc a { color: #fff; opacity: .85; text-decoration: none; margin-right: 14px; }
nav.toc a:hover { opacity: 1; text-decoration: underline; }
footer { color: var(--muted); font-size: 12px; text-align: center; margin-top: 12px; }
"#;
