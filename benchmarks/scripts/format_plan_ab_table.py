"""Plan times of two builds (benchmarks/scripts/plan_ab.sh) as a Markdown table: per scene and backend,
runs solved, median plan time of each build and their ratio, median k-NN time."""
import json, statistics as st, sys
from collections import defaultdict
rows=[json.loads(l) for l in open(sys.argv[1])]
d=defaultdict(lambda: defaultdict(list))
for r in rows:
    run=r['run']
    if not run: continue
    d[(run['name'],run['backend'])][r['build']].append(run)
print("| scene | backend | solved (before / after) | median plan s, before | after | after / before | k-NN s, before / after |")
print("| --- | --- | --- | --- | --- | --- | --- |")
for k in sorted(d):
    b=d[k]['before']; a=d[k]['after']
    mb=st.median(x['seconds'] for x in b); ma=st.median(x['seconds'] for x in a)
    kb=st.median(x['times']['knn'] for x in b); ka=st.median(x['times']['knn'] for x in a)
    print(f"| {k[0]} | {k[1]} | {sum(x['solved'] for x in b)}/{len(b)} / {sum(x['solved'] for x in a)}/{len(a)} | {mb:.3f} | {ma:.3f} | {ma/mb:.2f} | {kb:.2f} / {ka:.2f} |")
