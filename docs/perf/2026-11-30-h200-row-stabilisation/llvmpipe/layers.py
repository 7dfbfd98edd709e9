import json, sys
dx = float(sys.argv[1]); names = sys.argv[2:]
head = 1000 * 9.81 * dx
js = {n: json.load(open(n)) for n in names}
L = js[names[0]]['layers']
print('z      ref    ' + '  '.join(n.split('/')[-1][:12].rjust(12) for n in names))
for k, l in enumerate(L):
    row = [f"{l['z']:.4f} {l['reference']:7.1f}"]
    for n in names:
        m = js[n]['layers'][k]
        row.append(f"{(m['pressure'] - m['reference']) / head:12.2f}")
    print('  '.join(row))
for n in names:
    j = js[n]; print(n, 'interior', round(100*j['core_error_over_rho_g_H'],2) if 'core_error_over_rho_g_H' in j else '', 'floor', round(100*j['floor_error_over_rho_g_H'],2), 'pair', round(100*j['floor_pair_error_over_rho_g_H'],2), 'max', round(100*j['max_error_over_rho_g_H'],2))
