import json,sys,collections,math
rows=collections.defaultdict(list)
for line in open(sys.argv[1]):
    p=line.split(' ',4)
    s,i,v,r=p[:4]
    try: d=json.loads(p[4])
    except Exception: print('bad',line[:100]); continue
    rows[(s,i,v)].append(d)
variants=[v for v in sys.argv[2].split(',')]
scenes=[]
for k in rows:
    if k[0] not in scenes: scenes.append(k[0])
allr=collections.defaultdict(list)
for s in scenes:
    per=collections.defaultdict(list)
    for i in sorted({k[1] for k in rows if k[0]==s}):
        off=min(d['seconds'] for d in rows[(s,i,'off')])
        line=f"{s:15s} {i} off {off*1e3:7.1f}"
        for v in variants:
            t=min(d['seconds'] for d in rows[(s,i,v)])
            same=all(d['length']==rows[(s,i,'off')][0]['length'] for d in rows[(s,i,v)])
            b=min(rows[(s,i,v)],key=lambda d:d['seconds'])
            line+=f" | {v}: {t*1e3:7.1f} x{off/t:4.2f}{'' if same else ' DIFF'} sea {b['times']['search']*1e3:5.1f} edge {b['times']['edge_checks']*1e3:5.1f}"
            per[v].append(off/t); allr[v].append(off/t)
        print(line)
    print(s,' '.join(f"{v}: x{math.exp(sum(map(math.log,per[v]))/len(per[v])):.3f}" for v in variants))
print('ALL',' '.join(f"{v}: x{math.exp(sum(map(math.log,allr[v]))/len(allr[v])):.3f}" for v in variants))
