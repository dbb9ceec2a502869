#include "runtime/render/scene/emitters.h"

#include "kernels/common/accel/scene_view.h"
#include "runtime/render/scene/discrete_cdf.h"

namespace cohort {

EmitterTable build_emitter_table(const KdTree& tree, const std::vector<Material>& materials,
                                 const std::vector<std::uint32_t>& triangle_material) {
  EmitterTable table;
  std::vector<double> power;
  for (std::uint32_t i = 0; i < tree.triangles.size(); ++i) {
    const Material& m = materials[triangle_material[i]];
    const float area = 0.5f * v3_length(triangle_cross(&tree.triangles[i]));
    // the same function the kernel uses for MIS, so both sides agree on each triangle's power
    const float p = emitter_power(v3_from4(m.emission), area, material_two_sided_emission(&m));
    if (!(p > 0.f)) continue;
    table.entries.push_back(EmitterEntry{i, 0.f, 0.f, area});
    power.push_back(p);
  }
  const std::vector<float> cdf = discrete_cdf(power);
  double total = 0;
  for (double p : power) total += p;
  for (std::size_t i = 0; i < cdf.size(); ++i) {
    table.entries[i].cdf = cdf[i];
    table.entries[i].pmf = cdf_step(cdf, i);  // the pmf the estimator divides by
  }
  table.total_power = static_cast<float>(total);
  return table;
}

}  // namespace cohort
