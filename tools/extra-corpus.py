#!/usr/bin/env python3
"""Helpers of tools/extra-corpus.
  extra-corpus.py stl IN OUT HEIGHT_MM UP
      mesh (.off, binary or ASCII .stl) -> binary STL: the input axis UP
      (x, y, z, -x, -y, -z) becomes Z, scaled to HEIGHT_MM, XY-centred on the
      origin (the slicers centre it on the bed at 125,105), min z = 0.
  extra-corpus.py filament GCODE
      prints "total support layers": mm of filament of the extruding moves
      that travel in XY (retracts and primes excluded), all and those whose
      role contains "support" (;TYPE: lines, or Slic3r's per-line comments),
      and the number of distinct Z heights with extrusion.
  extra-corpus.py results BASELINE.md DEFAULT.md ZERO.md
      joins the baseline table (tests/data/corpus2/README.md) with two
      tools/corpus-table outputs into docs/results.md's corpus2 table."""
import re, struct, sys


def read_off(path):
    words = []
    with open(path) as f:
        for line in f:
            line = line.split('#', 1)[0]
            words.extend(line.split())
    if words[0].upper().endswith('OFF'):
        header = words[0]
        words = words[1:]
    nv, nf = int(words[0]), int(words[1])
    i = 3
    verts = []
    for _ in range(nv):
        verts.append(tuple(float(w) for w in words[i:i + 3]))
        i += 3
    tris = []
    for _ in range(nf):
        k = int(words[i])
        idx = [int(w) for w in words[i + 1:i + 1 + k]]
        i += 1 + k
        # a face line may carry a colour after its indices
        while i < len(words) and not words[i].lstrip('-').isdigit():
            i += 1
        for j in range(1, k - 1):  # fan
            tris.append((verts[idx[0]], verts[idx[j]], verts[idx[j + 1]]))
    return tris


def read_stl(path):
    data = open(path, 'rb').read()
    n = struct.unpack('<I', data[80:84])[0]
    if 84 + 50 * n == len(data):
        return [tuple(struct.unpack('<3f', data[84 + 50 * t + 12 + 12 * v:84 + 50 * t + 24 + 12 * v])
                      for v in range(3)) for t in range(n)]
    tris, cur = [], []
    for line in data.decode().splitlines():
        w = line.split()
        if w and w[0] == 'vertex':
            cur.append(tuple(float(x) for x in w[1:4]))
            if len(cur) == 3:
                tris.append(tuple(cur))
                cur = []
    return tris


# Rotations taking the named axis to +Z (proper rotations: orientation kept).
UP = {
    'z': lambda p: (p[0], p[1], p[2]),
    '-z': lambda p: (p[0], -p[1], -p[2]),
    'y': lambda p: (p[0], -p[2], p[1]),
    '-y': lambda p: (p[0], p[2], -p[1]),
    'x': lambda p: (-p[2], p[1], p[0]),
    '-x': lambda p: (p[2], p[1], -p[0]),
}


def filament(path):
    absolute, e, role, z = True, 0.0, '', 0.0
    total = support = 0.0
    zs = set()
    num = re.compile(r'([XYZEF])(-?[0-9.]+)')
    with open(path, errors='replace') as f:
        for line in f:
            if line.startswith(';TYPE:'):
                role = line[6:].strip().lower()
                continue
            code, _, comment = line.partition(';')
            w = code.split()
            if not w:
                continue
            if w[0] == 'M82':
                absolute = True
            elif w[0] == 'M83':
                absolute = False
            elif w[0] == 'G92':
                for k, v in num.findall(code):
                    if k == 'E':
                        e = float(v)
            elif w[0] in ('G0', 'G1', 'G2', 'G3'):
                p = dict(num.findall(code))
                if 'Z' in p:
                    z = float(p['Z'])
                if 'E' not in p:
                    continue
                de = float(p['E']) - e if absolute else float(p['E'])
                e = float(p['E']) if absolute else e + de
                if de > 0 and ('X' in p or 'Y' in p):
                    total += de
                    zs.add(round(z, 3))
                    r = comment.strip().lower() if comment.strip() else role
                    if 'support' in r:
                        support += de
    print('%.1f %.1f %d' % (total, support, len(zs)))


def results(baseline_md, default_md, zero_md):
    """docs/results.md's corpus2 table: tools/corpus-table's rows at the default
    and at --min-overhang-area 0, with the slicers' support from the baseline."""
    base={}
    for l in open(baseline_md):
        c=[x.strip() for x in l.strip().strip('|').split('|')]
        if len(c)<5 or not c[4].startswith('**'): continue
        key={'PrusaSlicer 2.5 (grid, defaults)':'p','Slic3r 1.3 (defaults)':'s','Cura 4.13 normal':'c','Cura 4.13 tree':'t'}[c[1]]
        base.setdefault(c[0],{})[key]=float(c[4].strip('*'))
    def rows(path):
        r={}
        for l in open(path):
            c=[x.strip() for x in l.strip().strip('|').split('|')]
            if len(c)<11 or c[2] not in ('pillars','scaffold'): continue
            r[(c[0],c[2])]=c
        return r
    d=rows(default_md)
    z=rows(zero_md)
    files=sorted({k[0] for k in d})
    print('| file | points | pillars mm | scaffold mm | PrusaSlicer mm | Slic3r mm | Cura mm | Cura tree mm | scaffold / PrusaSlicer | scaffold / Slic3r | scaffold / Cura tree | unheld mm², all (counted) (pillars / scaffold) | collisions mm² (pillars / scaffold) | support extruded twice mm² (pillars / scaffold) | check (pillars / scaffold) | at `--min-overhang-area 0`, checked with nothing forgiven: unheld mm² (pillars / scaffold) | print time min: original / pillars / scaffold | scaffold s |')
    print('|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---|---|---|---|---:|')
    tot={'pi':0,'sc':0,'p':0,'s':0,'c':0,'t':0}
    for f in files:
        m=f.split('.')[0]; b=base[m]; p=d[(f,'pillars')]; s=d[(f,'scaffold')]
        pi=float(p[4]); sc=float(s[4])
        for k,v in (('pi',pi),('sc',sc),('p',b['p']),('s',b['s']),('c',b['c']),('t',b['t'])): tot[k]+=v
        zz=' / '.join('%s %s'%(z[(f,mm)][5].split()[0], z[(f,mm)][8]) for mm in ('pillars','scaffold')) + ' (scaffold %.0f mm, %.0f %% of tree)'%(float(z[(f,'scaffold')][4]), 100*float(z[(f,'scaffold')][4])/b['t'])
        tp=re.match(r'([\d.]+) \(([\d.]+)\)',p[9]); ts=re.match(r'([\d.]+) \(([\d.]+)\)',s[9])
        print('| %s | %s | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f %% | %.0f %% | %.0f %% | %s / %s | %.2f / %.2f | %.0f / %.0f | %s / %s | %s | %s / %s / %s | %s |'%(
            f,s[3],pi,sc,b['p'],b['s'],b['c'],b['t'],100*sc/b['p'],100*sc/b['s'],100*sc/b['t'],p[5],s[5],float(p[6]),float(s[6]),float(p[7]),float(s[7]),p[8],s[8],zz,tp.group(2),tp.group(1),ts.group(1),s[10]))
    print('| **sum** | | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f %% | %.0f %% | %.0f %% | | | | | | | |'%(tot['pi'],tot['sc'],tot['p'],tot['s'],tot['c'],tot['t'],100*tot['sc']/tot['p'],100*tot['sc']/tot['s'],100*tot['sc']/tot['t']))


def main():
    if sys.argv[1] == 'filament':
        return filament(sys.argv[2])
    if sys.argv[1] == 'results':
        return results(*sys.argv[2:5])
    src, dst, height, up = sys.argv[2], sys.argv[3], float(sys.argv[4]), sys.argv[5]
    tris = read_stl(src) if src.lower().endswith('.stl') else read_off(src)
    rot = UP[up]
    tris = [tuple(rot(v) for v in t) for t in tris]
    pts = [v for t in tris for v in t]
    lo = [min(p[a] for p in pts) for a in range(3)]
    hi = [max(p[a] for p in pts) for a in range(3)]
    s = height / (hi[2] - lo[2])
    cx, cy = (lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2
    out = []
    for t in tris:
        q = [((v[0] - cx) * s, (v[1] - cy) * s, (v[2] - lo[2]) * s) for v in t]
        u = [q[1][a] - q[0][a] for a in range(3)]
        w = [q[2][a] - q[0][a] for a in range(3)]
        n = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
        ln = sum(c * c for c in n) ** 0.5
        if ln == 0:
            continue  # degenerate triangle
        out.append(struct.pack('<12fH', *(c / ln for c in n), *q[0], *q[1], *q[2], 0))
    with open(dst, 'wb') as f:
        f.write(b'mesh2stl'.ljust(80))
        f.write(struct.pack('<I', len(out)))
        f.write(b''.join(out))
    print('%d triangles, %.1f x %.1f x %.1f mm' % ( len(out), (hi[0] - lo[0]) * s,
          (hi[1] - lo[1]) * s, height))


main()
