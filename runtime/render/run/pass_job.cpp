#include "runtime/render/run/pass_job.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "runtime/render/run/adaptive.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

PassSchedule make_schedule(const RenderSettings& s, const RenderControl& control) {
  if (control.resume_from) {
    if (s.pass_samples && s.pass_samples != control.resume_from->pass_samples)
      throw InputError(fmt::format("--pass-spp {}: the checkpoint was rendered in passes of {} spp", s.pass_samples,
                                   control.resume_from->pass_samples));
    return {control.resume_from->pass_samples, control.resume_from->samples, s.spp, s.target_error > 0};
  }
  return {s.pass_samples ? s.pass_samples : default_pass_samples(s.width, s.height, s.spp), 0, s.spp,
          s.target_error > 0};
}

}  // namespace

Image film_image(const FilmState& film) {
  Image image(static_cast<int>(film.width), static_cast<int>(film.height));
  const float uniform = film.samples ? 1.f / static_cast<float>(film.samples) : 0.f;
  for (std::size_t i = 0; i < film.sums.size(); ++i) {
    // adaptive sampling: each pixel by its own count
    const std::uint32_t n = film.pixel_samples.empty() ? film.samples : film.pixel_samples[i];
    const float inv = film.pixel_samples.empty() ? uniform : (n ? 1.f / static_cast<float>(n) : 0.f);
    image.rgb[3 * i + 0] = film.sums[i].x * inv;
    image.rgb[3 * i + 1] = film.sums[i].y * inv;
    image.rgb[3 * i + 2] = film.sums[i].z * inv;
  }
  return image;
}

std::size_t pass_window(std::size_t devices, std::size_t film_bytes) {
  const std::size_t budget = (std::size_t(2) << 30) / std::max<std::size_t>(film_bytes, 1);
  return std::max(devices + 1, std::min(4 * devices, budget));
}

PassJob::PassJob(const RenderSettings& settings, const ProgressCallback& progress, const RenderControl& control,
                 std::size_t window, std::size_t devices)
    : settings_(settings), progress_(progress), control_(control), schedule_(make_schedule(settings, control)),
      window_(std::max<std::size_t>(window, 1)), devices_(devices) {
  const std::size_t pixels = std::size_t(settings.width) * settings.height;
  film_.width = settings.width;
  film_.height = settings.height;
  film_.pass_samples = schedule_.pass_samples();
  if (control.resume_from) {
    const FilmState& f = *control.resume_from;
    if (f.width != settings.width || f.height != settings.height || f.sums.size() != pixels)
      throw InputError(fmt::format("the checkpoint is {}x{}, the render {}x{}", f.width, f.height, settings.width,
                                   settings.height));
    if (!f.pixel_samples.empty() && f.pixel_samples.size() != pixels)
      throw InputError(fmt::format("the checkpoint counts samples of {} pixels, the render has {}",
                                   f.pixel_samples.size(), pixels));
    if (settings.target_error > 0 && f.pixel_samples.empty() && f.samples > 0)
      throw InputError("--target-error: the checkpoint was rendered without it");
    film_ = f;
    resumed_samples_ = f.samples;
  } else {
    film_.sums.assign(pixels, co_float4{0, 0, 0, 0});
    if (settings.target_error > 0) film_.pixel_samples.assign(pixels, 0);
  }
}

bool PassJob::choose_round_pixels(const SamplePass& pass) {
  const std::uint32_t start = round_start(pass.first_sample);
  if (round_chosen_ && start == round_start_) return true;
  // the decision reads the film at the round's start: every earlier pass must be in it
  if (combined_ != handed_out_) return false;
  if (image_on_device_ && read_image_) film_.sums = read_image_();
  round_pixels_ = std::make_shared<const std::vector<std::uint32_t>>(
      pass.first_sample == start ? round_pixels(film_, start, settings_.target_error)
                                 : pixels_with_samples(film_, pass.first_sample));  // resumed inside a round
  round_start_ = start;
  round_chosen_ = true;
  return true;
}

void PassJob::device_ready() {
  const std::lock_guard lock(mutex_);
  ++ready_;
  changed_.notify_all();
}

PassJob::Offer PassJob::offer(SamplePass& pass) {
  if (!ended_ && !aborted_ && ready_ < devices_) return Offer::wait;
  if (!ended_) {
    if (!start_) start_ = Clock::now();  // the render clock starts with the first pass, after compiling
    const double elapsed = seconds_since_start();
    if (aborted_ || (control_.stop_requested && control_.stop_requested())) {
      interrupted_ = !aborted_;
      ended_ = true;
    } else if (settings_.time_limit > 0 && elapsed >= settings_.time_limit) {
      ended_ = true;
    } else if (const auto p = schedule_.pass(handed_out_)) {
      if (handed_out_ - combined_ >= window_) return Offer::wait;
      if (settings_.target_error > 0 && !choose_round_pixels(*p)) return Offer::wait;
      if (settings_.target_error > 0 && round_pixels_->empty()) {
        ended_ = true;  // every tile has its share of samples
      } else {
        pass = *p;
        if (settings_.target_error > 0 && round_pixels_->size() < film_.sums.size()) pass.pixels = round_pixels_;
        if (settings_.target_error > 0) handed_out_pixels_.emplace(pass.index, pass.pixels);
        ++handed_out_;
        return Offer::pass;
      }
    } else {
      ended_ = true;
    }
    if (ended_) changed_.notify_all();
  }
  return Offer::end;
}

std::optional<SamplePass> PassJob::next() {
  std::unique_lock lock(mutex_);
  SamplePass pass;
  for (;;) {
    const Offer o = offer(pass);
    if (o == Offer::pass) return pass;
    if (o == Offer::end) return std::nullopt;
    changed_.wait(lock);
  }
}

PassJob::Offer PassJob::try_next(SamplePass& pass) {
  const std::lock_guard lock(mutex_);
  return offer(pass);
}

const FilmState* PassJob::device_keeps_image(std::function<std::vector<co_float4>()> read_image) {
  const std::lock_guard lock(mutex_);
  // the device continues from the film as combined so far: nothing else may be out (one device
  // may render the passes in turns, as --method auto's probe does, each time from where the last
  // turn left the image)
  if (devices_ != 1 || combine_on_host_ || image_on_device_ || combined_ != handed_out_ || !waiting_.empty())
    return nullptr;
  image_on_device_ = true;
  read_image_ = std::move(read_image);
  return &film_;
}

void PassJob::deliver_image(std::vector<co_float4> sums) {
  const std::lock_guard lock(mutex_);
  if (sums.size() != film_.sums.size())
    throw DeviceError(fmt::format("an image film of {} pixels for an image of {}", sums.size(), film_.sums.size()));
  film_.sums = std::move(sums);
  image_on_device_ = false;
  read_image_ = {};
  changed_.notify_all();
}

void PassJob::combine(const PassFilm& f) {
  std::array<double, 4> mean{0, 0, 0, double(f.pass.samples)};
  if (image_on_device_ && f.sums.empty()) {
    // the device added the pass to the image it keeps; only its totals come here
    mean[0] = f.totals[0];
    mean[1] = f.totals[1];
    mean[2] = f.totals[2];
  }
  // the same float additions whichever device or rank rendered the pass: this order is the image
  for (std::size_t i = 0; i < f.sums.size(); ++i) {
    film_.sums[i].x += f.sums[i].x;
    film_.sums[i].y += f.sums[i].y;
    film_.sums[i].z += f.sums[i].z;
    film_.sums[i].w += f.sums[i].w;
    mean[0] += f.sums[i].x;
    mean[1] += f.sums[i].y;
    mean[2] += f.sums[i].z;
  }
  // the pixels as handed out (a film from another rank carries the pass's index and samples only)
  PixelList pixels;
  if (const auto it = handed_out_pixels_.find(f.pass.index); it != handed_out_pixels_.end()) {
    pixels = it->second;
    handed_out_pixels_.erase(it);
  }
  const std::size_t pass_pixels = pixels ? pixels->size() : film_.sums.size();
  for (int c = 0; c < 3; ++c) mean[c] /= std::max(1.0, double(pass_pixels) * f.pass.samples);
  pass_means_.push_back(mean);
  if (!film_.pixel_samples.empty()) {
    if (pixels) {
      for (const std::uint32_t pixel : *pixels) film_.pixel_samples[pixel] += f.pass.samples;
    } else {
      for (auto& n : film_.pixel_samples) n += f.pass.samples;
    }
  }
  film_.samples = f.pass.first_sample + f.pass.samples;
  film_.dropped_samples += f.dropped;
}

void PassJob::deliver(PassFilm film) {
  if (film.sums.size() != film_.sums.size() && !(image_on_device_ && film.sums.empty()))
    throw DeviceError(fmt::format("pass {}: a partial film of {} pixels for an image of {}", film.pass.index,
                                  film.sums.size(), film_.sums.size()));
  std::unique_lock lock(mutex_);
  rays_ += film.rays;
  const std::uint32_t index = film.pass.index;
  waiting_.emplace(index, std::move(film));
  for (auto it = waiting_.find(combined_); it != waiting_.end(); it = waiting_.find(combined_)) {
    combine(it->second);
    waiting_.erase(it);
    ++combined_;
    last_combined_ = Clock::now();
    const double seconds = seconds_since_start();
    if (progress_) progress_({film_.samples, settings_.time_limit > 0 && settings_.spp == 0 ? 0u : settings_.spp, rays_,
                              seconds});
    if (control_.checkpoint && control_.checkpoint_seconds > 0 &&
        seconds - last_checkpoint_ >= control_.checkpoint_seconds) {
      if (image_on_device_ && read_image_) film_.sums = read_image_();
      control_.checkpoint(film_);
      last_checkpoint_ = seconds;
    }
  }
  changed_.notify_all();
}

void PassJob::abort() {
  const std::lock_guard lock(mutex_);
  aborted_ = ended_ = true;
  changed_.notify_all();
}

bool PassJob::aborted() const {
  const std::lock_guard lock(mutex_);
  return aborted_;
}

bool PassJob::finished() const {
  const std::lock_guard lock(mutex_);
  return ended_ && combined_ == handed_out_ && !image_on_device_;
}

FilmState PassJob::finish() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return aborted_ || (ended_ && combined_ == handed_out_ && !image_on_device_); });
  if (aborted_) throw DeviceError("the render was aborted");
  if (control_.checkpoint) control_.checkpoint(film_);
  return film_;
}

FilmState PassJob::finish_into(RenderResult& result) {
  FilmState film = finish();
  result.image = film_image(film);
  result.samples = film.samples;
  result.resumed_samples = resumed_samples();
  result.dropped_samples = film.dropped_samples;
  result.interrupted = interrupted();
  result.render_seconds = seconds();
  return film;
}

PassJob::ImageMean PassJob::image_mean() const {
  const std::lock_guard lock(mutex_);
  ImageMean result;
  double samples = 0;
  for (const auto& m : pass_means_) samples += m[3];
  if (samples <= 0) return result;
  for (int c = 0; c < 3; ++c) {
    for (const auto& m : pass_means_) result.mean[c] += m[c] * m[3] / samples;
    if (pass_means_.size() < 2) continue;
    double spread = 0;
    for (const auto& m : pass_means_) spread += m[3] / samples * (m[c] - result.mean[c]) * (m[c] - result.mean[c]);
    const double k = double(pass_means_.size());
    result.standard_error[c] = std::sqrt(spread * k / (k - 1) / k);
  }
  return result;
}

bool PassJob::interrupted() const {
  const std::lock_guard lock(mutex_);
  return interrupted_;
}

std::uint64_t PassJob::rays() const {
  const std::lock_guard lock(mutex_);
  return rays_;
}

double PassJob::seconds_since_start() const {
  return start_ ? std::chrono::duration<double>(Clock::now() - *start_).count() : 0.0;
}

double PassJob::seconds() const {
  const std::lock_guard lock(mutex_);
  if (!start_) return 0.0;
  const bool outstanding = combined_ < handed_out_;
  const Clock::time_point end = outstanding || !last_combined_ ? Clock::now() : *last_combined_;
  return std::chrono::duration<double>(end - *start_).count();
}

}  // namespace cohort
