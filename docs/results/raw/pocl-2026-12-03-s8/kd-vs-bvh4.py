import json,sys
names=['dragon-100k','armadillo','conference','damaged-helmet','crytek-sponza']
print('| scene | view | method | KD compact M samples/CPU-s | BVH4 | BVH4 / KD | KD wall M samples/s | BVH4 wall | ratio |')
print('|---|---|---|---:|---:|---:|---:|---:|---:|')
for n in names:
    kd=json.load(open(f'{sys.argv[1]}/cohort/{n}.json'))['scenes'][0]
    bv=json.load(open(f'{sys.argv[2]}/cohort/{n}.json'))['scenes'][0]
    for vk,vb in zip(kd['views'],bv['views']):
        for m in ['naive','sc']:
            a=vk['path_tracing'][m]; b=vb['path_tracing'][m]
            c1=a['msamples_per_cpu_second']['median']; c2=b['msamples_per_cpu_second']['median']
            w1=a['msamples_per_second']['median']; w2=b['msamples_per_second']['median']
            print(f"| {n} | {vk['view']['name'] if isinstance(vk['view'],dict) else vk['view']} | {m} | {c1:.3f} | {c2:.3f} | {c2/c1:.2f}x | {w1:.3f} | {w2:.3f} | {w2/w1:.2f}x |")
    print(f"<!-- {n}: kd {kd['kdtree'].get('kind')} bvh {bv['kdtree'].get('kind')} -->")
