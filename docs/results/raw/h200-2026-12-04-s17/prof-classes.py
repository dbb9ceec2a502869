p='runtime/accel/kdtree_builder.cpp'
s=open(p).read()
s=s.replace('#include <utility>\n','#include <utility>\n#include <x86intrin.h>\n#include <atomic>\n#include <cstdio>\n#include <cstdlib>\n',1)
s=s.replace('namespace cohort::kd {\nnamespace {\n','''namespace cohort::kd {
namespace prof { std::atomic<unsigned long long> n[20], search[20], part[20], leafsearch[20], other[20]; 
int cls(std::size_t c){int k=0; while((std::size_t(1)<<k) < c && k<19) ++k; return k;} }
namespace {
''',1)
s=s.replace('''  const SplitPlane plane = find_plane(s, begin, end, context, parallel, inherited);''','''  const int K = prof::cls(count); const auto T0=__rdtsc();
  const SplitPlane plane = find_plane(s, begin, end, context, parallel, inherited);
  const auto T1=__rdtsc(); prof::n[K]+=1; prof::search[K]+=T1-T0;''')
s=s.replace('''  if (!plane.valid() || !(split_cost <= options_.intersection_cost * static_cast<float>(count))) {
    return make_leaf''','''  if (!plane.valid() || !(split_cost <= options_.intersection_cost * static_cast<float>(count))) {
    prof::leafsearch[K]+=1;
    return make_leaf''')
s=s.replace('''  const std::array<std::size_t, 2> counts =
      partition(s.refs, begin, end, voxel, plane, triangles_, s.right, clipped);''','''  const auto T2=__rdtsc();
  const std::array<std::size_t, 2> counts =
      partition(s.refs, begin, end, voxel, plane, triangles_, s.right, clipped);
  prof::part[K]+=__rdtsc()-T2;''')
s=s.replace('''  builder.build(out, scratch, 0, triangles.size(), bounds, 0, 0);
''','''  builder.build(out, scratch, 0, triangles.size(), bounds, 0, 0);
  if (getenv("PROF")) { double tot=0; for(int k=0;k<20;++k) tot+=prof::search[k]+prof::part[k];
  for(int k=0;k<20;++k) if(prof::n[k]) std::fprintf(stderr,"cls<=%6d nodes %8llu leafafter %8llu search %.1f%% (%5.0f cyc/node) part %.1f%% (%5.0f cyc/node)\\n",1<<k,(unsigned long long)prof::n[k],(unsigned long long)prof::leafsearch[k],100*prof::search[k]/tot,double(prof::search[k])/prof::n[k],100*prof::part[k]/tot,double(prof::part[k])/prof::n[k]);
  std::fprintf(stderr,"total search+part cycles %.3g\\n",tot); }
  for(int k=0;k<20;++k) prof::n[k]=prof::search[k]=prof::part[k]=prof::leafsearch[k]=0;
''')
open(p,'w').write(s)
