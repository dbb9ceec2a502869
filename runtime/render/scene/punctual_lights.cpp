#include "runtime/render/scene/punctual_lights.h"

#include <cmath>

#include "kernels/common/accel/scene_view.h"
#include "runtime/render/scene/discrete_cdf.h"

namespace cohort {

double punctual_power(const SceneLight& light) {
  const double i = luminance(v3(light.intensity.x, light.intensity.y, light.intensity.z));
  if (light.type == SceneLight::Type::point) return 4 * M_PI * i;
  return 2 * M_PI * (1 - std::cos(0.5 * (double(light.inner_cone) + light.outer_cone))) * i;
}

PunctualTable make_punctual_table(const std::vector<SceneLight>& lights) {
  PunctualTable t;
  std::vector<double> power;
  for (const SceneLight& l : lights) {
    const double p = punctual_power(l);
    if (!(p > 0)) continue;  // black lights add nothing; NEE never picks them
    PunctualLight d{};
    d.position = {l.position.x, l.position.y, l.position.z, 0.f};
    d.direction = {l.direction.x, l.direction.y, l.direction.z, std::cos(l.outer_cone)};
    d.intensity = {l.intensity.x, l.intensity.y, l.intensity.z, std::cos(l.inner_cone)};
    d.type = l.type == SceneLight::Type::spot ? PUNCTUAL_SPOT : PUNCTUAL_POINT;
    t.lights.push_back(d);
    power.push_back(p);
    t.power += p;
  }
  const std::vector<float> cdf = discrete_cdf(power);
  for (std::size_t i = 0; i < cdf.size(); ++i) {
    t.lights[i].cdf = cdf[i];
    t.lights[i].pmf = cdf_step(cdf, i);  // the pmf the estimator divides by
  }
  return t;
}

}  // namespace cohort
