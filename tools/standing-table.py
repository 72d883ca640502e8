#!/usr/bin/env python3
"""Prints tools/standing-table's markdown from its WORK folder: one folder per
model holding scaffold-check's JSON reports (in.json of the input alone,
cura_in.json of Cura's no-support file of the model, scS.json at --min-stiffness S
with its exit status in scS.rc, scS.at2.json the same output at the default
2 N/mm; prusa/tree/normal.json the slicers' own supports checked alone, or
NAME.missing when the slicer wrote no file).
Usage: standing-table.py WORK"""
import json, os, sys

SCAFFOLD = [('sc1', 'scaffold @1'), ('sc2', 'scaffold @2'), ('sc5', 'scaffold @5')]
SLICERS = [('prusa', 'PrusaSlicer 2.5 grid'), ('tree', 'Cura 4.13 tree'), ('normal', 'Cura 4.13 normal')]
SHORT = {'sc1': '@1', 'sc2': '@2', 'sc5': '@5', 'prusa': 'grid', 'tree': 'tree', 'normal': 'normal'}
RULE_K = 2.0  # the Standing rule's default, N/mm


def load(path):
    if not os.path.exists(path):
        return None
    try:
        with open(path) as f:
            return json.load(f)
    except ValueError:
        return None


def num(k):
    """Stiffness in N/mm with about three significant digits."""
    if k >= 100:
        return '%.0f' % k
    if k >= 10:
        return '%.1f' % k
    if k >= 1:
        return '%.2f' % k
    return '%.3f' % k


def weakest(side):
    if side['islands'] == 0:
        return 'none'
    if side['floating']:
        return 'floating; %s' % num(side['weakest_standing_k']) if side['weakest_standing_k'] >= 0 else 'floating'
    return num(side['weakest_k'])


def main(work):
    models = sorted((d for d in os.listdir(work) if os.path.exists(os.path.join(work, d, 'corpus'))),
                    key=lambda d: (open(os.path.join(work, d, 'corpus')).read().strip(), d))
    cols = SCAFFOLD + SLICERS
    head = ['model', 'no support min']
    for key, _ in cols:
        if key == 'tree':
            head.append('Cura no support min')
        head += ['%s mm' % SHORT[key], '%s min' % SHORT[key], '%s k' % SHORT[key]]
    print('| ' + ' | '.join(head) + ' |')
    print('|---|---:|' + '---:|' * (3 * len(cols) + 1))
    stats = {key: dict(models=0, with_support=0, stand=0, stand_rooted=0, check=0, travels=0, weak_travels=0, under_mm=0.0)
             for key, _ in cols}
    sums = {key: [0.0, 0.0] for key, _ in cols}
    plain_min = cura_min = 0.0
    complete = []
    missing = []
    for m in models:
        d = os.path.join(work, m)
        plain = load(os.path.join(d, 'in.json'))
        row = [m, '%.1f' % (plain['print_time_s'] / 60) if plain else '–']
        plain_min += plain['print_time_s'] / 60 if plain else 0
        have_all = True
        for key, label in cols:
            if key == 'tree':
                cura = load(os.path.join(d, 'cura_in.json'))
                row.append('%.1f' % (cura['print_time_s'] / 60) if cura else '–')
                cura_min += cura['print_time_s'] / 60 if cura else 0
            r = load(os.path.join(d, key + '.json'))
            if r is None:
                why = 'slicer wrote no file' if os.path.exists(os.path.join(d, key + '.missing')) else 'no report'
                missing.append('%s, %s: %s' % (m, label, why))
                row += ['–', '–', '–']
                have_all = False
                continue
            side = r['standing']['added']
            cell = weakest(side)
            if key.startswith('sc'):
                rc = open(os.path.join(d, key + '.rc')).read().strip()
                cell += ' ' + {'0': 'PASS', '1': 'FAIL'}.get(rc, 'error')
                if rc == '0':
                    stats[key]['check'] += 1
            # judged at 2 N/mm: the slicers' and scaffold @2's own reports, the
            # @1 and @5 outputs checked again at the default
            at2 = load(os.path.join(d, key + '.at2.json')) or r
            s2 = at2['standing']['added']
            st = stats[key]
            st['models'] += 1
            st['with_support'] += side['islands'] > 0
            st['stand'] += s2['under'] == 0
            st['stand_rooted'] += s2['weakest_standing_k'] < 0 or s2['weakest_standing_k'] >= RULE_K
            st['travels'] += s2['travels']
            st['weak_travels'] += s2['weak_travels']
            st['under_mm'] += s2['under_filament_mm']
            row += ['%.0f' % r['support_filament_mm'], '%.1f' % (r['print_time_s'] / 60), cell]
            sums[key][0] += r['support_filament_mm']
            sums[key][1] += r['print_time_s'] / 60
        if have_all:
            complete.append(m)
        print('| ' + ' | '.join(row) + ' |')
    if len(complete) == len(models):
        cells = ['**sum**', '%.1f' % plain_min]
        for key, _ in cols:
            if key == 'tree':
                cells.append('%.1f' % cura_min)
            cells += ['%.0f' % sums[key][0], '%.1f' % sums[key][1], '']
        print('| ' + ' | '.join(cells) + ' |')
    print()
    if missing:
        print('No file: ' + '; '.join(missing) + '.')
        print()
    print('| configuration | models | stand at %g N/mm (no island under it) | the same, floating islands left out | '
          'scaffold-check at its own `--min-stiffness` | support filament mm | of it in islands under %g N/mm | '
          'travels over fresh support | of them over islands under %g N/mm |' % (RULE_K, RULE_K, RULE_K))
    print('|---|---:|---:|---:|---:|---:|---:|---:|---:|')
    for key, label in cols:
        st = stats[key]
        total = sums[key][0]
        print('| %s | %d | %d of %d | %d of %d | %s | %.0f | %.0f (%.1f %%) | %d | %d |' % (
            label, st['models'], st['stand'], st['models'], st['stand_rooted'], st['models'],
            ('%d of %d PASS' % (st['check'], st['models'])) if key.startswith('sc') else '–',
            total, st['under_mm'], 100 * st['under_mm'] / total if total else 0, st['travels'], st['weak_travels']))


main(sys.argv[1])
