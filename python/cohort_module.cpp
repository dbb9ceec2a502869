// The compiled part of the `cohort` Python package (python/cohort/__init__.py wraps it): a loaded
// scene per scene (SceneCommands, runtime/cli/scene_commands.h), renders run with the GIL released, images
// handed to NumPy without a copy, and Ctrl-C turned into a stop between passes.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/array.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "runtime/backend/device_support.h"
#include "runtime/backend/open_device.h"
#include "runtime/cli/cli.h"
#include "runtime/cli/scene_commands.h"
#include "runtime/image/denoiser.h"
#include "runtime/util/error.h"

namespace nb = nanobind;
using namespace nb::literals;

namespace cohort {
namespace {

// A float32 array over `values` (moved in: the array owns them, nothing is copied).
nb::ndarray<nb::numpy, float> owned_array(std::vector<float> values, std::initializer_list<std::size_t> shape) {
  auto owner = std::make_unique<std::vector<float>>(std::move(values));
  float* data = owner->data();
  // the capsule frees the vector when NumPy lets the array go
  nb::capsule free_owner(owner.get(), [](void* p) noexcept { std::unique_ptr<std::vector<float>>(static_cast<std::vector<float>*>(p)); });
  owner.release();
  return nb::ndarray<nb::numpy, float>(data, shape, free_owner);
}

nb::ndarray<nb::numpy, float> image_array(Image image) {
  const auto h = static_cast<std::size_t>(image.height), w = static_cast<std::size_t>(image.width);
  return owned_array(std::move(image.rgb), {h, w, 3});
}

std::string devices_json() {
  nlohmann::json out = nlohmann::json::array();
  std::vector<DeviceInfo> opencl;
  try {
    opencl = list_backend_devices(Backend::opencl);
  } catch (const InputError&) {  // no OpenCL device: an empty list, as `cohort devices` says
  }
  for (const auto& d : opencl) {
    const DeviceSupport s = device_support(d);
    out.push_back({{"backend", "opencl"}, {"index", d.device_index}, {"name", d.name}, {"platform", d.platform_name},
                   {"kind", d.is_gpu ? "gpu" : (d.is_cpu ? "cpu" : "other")}, {"compute_units", d.compute_units},
                   {"local_memory", d.local_memory}, {"local_memory_is_global", d.local_memory_is_global},
                   {"global_memory", d.global_memory}, {"max_allocation", d.max_allocation},
                   {"version", d.version}, {"driver", d.driver_version}, {"opencl_c", d.opencl_c_version},
                   {"max_work_group", d.max_work_group}, {"subgroups", d.subgroups},
                   {"correctly_rounded_divide_sqrt", d.correctly_rounded_divide_sqrt}, {"denormals", d.denormals},
                   {"images", d.image_support}, {"runs", s.runs}, {"refusal", s.refusal},
                   {"work_group", s.work_group}, {"pth_levels", s.pth_levels},
                   {"pth_local_bytes", s.local_budget}, {"prefetch", s.prefetch}, {"sorts", s.sorts},
                   {"sort_refusal", s.sort_refusal}});
  }
  if (cuda_backend_built()) {
    try {
      for (const auto& d : list_backend_devices(Backend::cuda))
        out.push_back({{"backend", "cuda"}, {"index", d.device_index}, {"name", d.name}, {"platform", "CUDA"},
                       {"kind", "gpu"}, {"compute_units", d.compute_units}, {"local_memory", d.local_memory},
                       {"global_memory", d.global_memory}, {"version", d.version}, {"driver", d.driver_version},
                       {"runs", true}});
    } catch (const InputError&) {  // no usable CUDA GPU
    }
  }
  return out.dump();
}

// A loaded scene whose render runs on its own thread while the calling thread, holding the GIL only for
// moments, forwards progress to Python and watches for Ctrl-C.
class PyScene {
 public:
  explicit PyScene(const std::vector<std::string>& arguments) : scene_(parse_render_arguments(arguments)) {}
  PyScene(const PyScene&) = delete;
  PyScene& operator=(const PyScene&) = delete;

  std::string info() {
    nb::gil_scoped_release release;
    return scene_.info().dump();
  }

  nb::dict render(const std::vector<std::string>& arguments, std::optional<std::array<float, 10>> camera,
                  nb::object progress, const std::vector<std::string>& venvs) {
    const RenderCommand command = parse_render_arguments(arguments);
    std::optional<SceneCamera> scene_camera;
    if (camera) {
      const auto& c = *camera;
      scene_camera = SceneCamera{{c[0], c[1], c[2]}, {c[3], c[4], c[5]}, {c[6], c[7], c[8]}, c[9]};
    }
    std::atomic<bool> stop{false};
    std::mutex mutex;
    std::condition_variable changed;
    std::optional<Progress> latest;
    bool done = false;
    const RenderHooks hooks{.stop_requested = [&] { return stop.load(); },
                            .progress = [&](const Progress& p) {
                              const std::lock_guard lock(mutex);
                              latest = p;
                            }};
    SceneRender result;
    std::exception_ptr failure;
    std::optional<nb::python_error> python_failure;  // Ctrl-C, or what `progress` raised
    const std::vector<std::filesystem::path> venv_paths(venvs.begin(), venvs.end());
    {
      nb::gil_scoped_release release;
      std::thread worker([&] {
        try {
          result = scene_.render(command, scene_camera, hooks, venv_paths);
        } catch (...) {
          failure = std::current_exception();
        }
        const std::lock_guard lock(mutex);
        done = true;
        changed.notify_all();
      });
      std::unique_lock lock(mutex);
      while (!done) {
        changed.wait_for(lock, std::chrono::milliseconds(50));
        std::optional<Progress> report;
        std::swap(report, latest);
        lock.unlock();
        {
          nb::gil_scoped_acquire acquire;
          if (!python_failure) {
            try {
              if (PyErr_CheckSignals() != 0) throw nb::python_error();
              if (report && !progress.is_none()) {
                nb::dict p;
                p["samples"] = report->samples_done;
                p["target"] = report->samples_target;
                p["rays"] = report->rays;
                p["seconds"] = report->seconds;
                progress(p);
              }
            } catch (nb::python_error& e) {
              python_failure.emplace(std::move(e));
              stop = true;  // the render ends after its current pass
            }
          }
        }
        lock.lock();
      }
      lock.unlock();
      worker.join();
    }
    if (python_failure) throw std::move(*python_failure);
    if (failure) std::rethrow_exception(failure);
    nb::dict aovs;
    if (result.aovs) {
      const auto h = static_cast<std::size_t>(result.image.height), w = static_cast<std::size_t>(result.image.width);
      aovs["albedo"] = image_array(std::move(result.aovs->albedo));
      aovs["normal"] = image_array(std::move(result.aovs->normal));
      aovs["depth"] = owned_array(std::move(result.aovs->depth), {h, w});
    }
    nb::dict out;
    out["image"] = image_array(std::move(result.image));
    out["aovs"] = aovs;
    out["denoised"] = result.denoised ? nb::cast(image_array(std::move(*result.denoised))) : nb::none();
    out["stats"] = result.stats.dump();
    out["interrupted"] = result.interrupted;
    return out;
  }

 private:
  SceneCommands scene_;
};

}  // namespace
}  // namespace cohort

NB_MODULE(_cohort, m) {
  nb::exception<cohort::InputError>(m, "InputError", PyExc_ValueError);
  nb::exception<cohort::DeviceError>(m, "DeviceError", PyExc_RuntimeError);
  nb::exception<cohort::DenoiserUnavailable>(m, "DenoiseError", PyExc_RuntimeError);
  m.def("devices_json", &cohort::devices_json, "Every device as JSON, with what Cohort does there");
  m.def("read_exr", [](const std::string& path) { return cohort::image_array(cohort::read_exr(path)); }, "path"_a,
        "An OpenEXR file's R, G, B as float32 (H, W, 3)");
  m.def("read_exr_channel", [](const std::string& path, const std::string& channel) {
        std::vector<float> values = cohort::read_exr_channel(path, channel);
        const cohort::Image header = cohort::read_exr(path);
        return cohort::owned_array(std::move(values), {std::size_t(header.height), std::size_t(header.width)});
      }, "path"_a, "channel"_a, "One float channel of an OpenEXR file (an AOV: albedo.R, N.X, depth.Z) as (H, W)");
  nb::class_<cohort::PyScene>(m, "LoadedScene")
      .def(nb::init<const std::vector<std::string>&>(), "arguments"_a)
      .def("info", &cohort::PyScene::info)
      .def("render", &cohort::PyScene::render, "arguments"_a, "camera"_a.none(), "progress"_a.none(),
           "venvs"_a);
}
