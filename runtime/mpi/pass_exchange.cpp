#include "runtime/mpi/pass_exchange.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <iterator>
#include <list>
#include <climits>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "runtime/render/run/adaptive.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

enum Tag : int { kRequest = 1, kAssign = 2, kFilm = 3 };

// The fixed part of a film message; the per-pixel sums follow it.
struct FilmHeader {
  std::uint32_t index, first_sample, samples, pad;
  std::uint64_t dropped, rays;
};

constexpr auto kIdle = std::chrono::microseconds(500);

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) {
    char text[MPI_MAX_ERROR_STRING] = {};
    int length = 0;
    MPI_Error_string(code, text, &length);
    throw DeviceError(fmt::format("{} failed: {}", what, std::string(text, static_cast<std::size_t>(length))));
  }
}

int film_message_bytes(std::size_t pixels) {
  const std::size_t bytes = sizeof(FilmHeader) + pixels * sizeof(co_float4);
  if (bytes > std::size_t(INT_MAX))
    throw InputError(fmt::format("{} pixels: a partial film is over the 2 GiB of one MPI message", pixels));
  return static_cast<int>(bytes);
}

// Assignments rank 0 has sent but MPI may not have delivered: an adaptive pass's pixel list makes
// one too long to go out eagerly, and a blocking send would wait for a rank that is itself blocked
// sending rank 0 a film. Each message stays here until its send completes.
class AssignmentSends {
 public:
  AssignmentSends() = default;
  AssignmentSends(const AssignmentSends&) = delete;
  AssignmentSends& operator=(const AssignmentSends&) = delete;
  ~AssignmentSends() {
    // after a failure: cancel and free what is still out (the job is ending anyway)
    for (auto& s : sends_) {
      MPI_Cancel(&s.request);
      MPI_Request_free(&s.request);
    }
  }

  // samples 0: no more passes for this rank; an adaptive pass's pixel list follows the three words
  void send(int rank, const SamplePass* pass) {
    Send s;
    s.message = {pass ? pass->index : 0, pass ? pass->first_sample : 0, pass ? pass->samples : 0};
    if (pass && pass->pixels) s.message.insert(s.message.end(), pass->pixels->begin(), pass->pixels->end());
    if (s.message.size() > std::size_t(INT_MAX)) throw InputError("a pass's pixel list is over one MPI message");
    check(MPI_Isend(s.message.data(), static_cast<int>(s.message.size()), MPI_UINT32_T, rank, kAssign, MPI_COMM_WORLD,
                    &s.request),
          "MPI_Isend of a pass assignment");
    sends_.push_back(std::move(s));  // the vector's buffer does not move with it
  }

  // Forgets the sends that completed; true when any did.
  bool reap() {
    const std::size_t before = sends_.size();
    for (auto it = sends_.begin(); it != sends_.end();) {
      int done = 0;
      check(MPI_Test(&it->request, &done, MPI_STATUS_IGNORE), "MPI_Test of a pass assignment");
      it = done ? sends_.erase(it) : std::next(it);
    }
    return sends_.size() != before;
  }
  bool empty() const { return sends_.empty(); }

 private:
  struct Send {
    std::vector<std::uint32_t> message;
    MPI_Request request = MPI_REQUEST_NULL;
  };
  std::list<Send> sends_;
};

// The pass of an assignment message (samples 0: no more passes).
SamplePass read_assignment(const std::vector<std::uint32_t>& message, PixelList& last_list) {
  if (message.size() < 3) throw DeviceError("rank 0 sent a pass assignment of fewer than three words");
  SamplePass pass{message[0], message[1], message[2], nullptr};
  if (message.size() > 3) {
    // the passes of one round share one list, as on rank 0 (a device uploads it once per round)
    if (!last_list || !std::equal(message.begin() + 3, message.end(), last_list->begin(), last_list->end()))
      last_list = std::make_shared<const std::vector<std::uint32_t>>(message.begin() + 3, message.end());
    pass.pixels = last_list;
  }
  return pass;
}

PassFilm receive_film(int rank, std::size_t pixels) {
  std::vector<char> bytes(static_cast<std::size_t>(film_message_bytes(pixels)));
  MPI_Status status;
  check(MPI_Recv(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, rank, kFilm, MPI_COMM_WORLD, &status),
        "MPI_Recv of a partial film");
  FilmHeader h;
  std::memcpy(&h, bytes.data(), sizeof(h));
  PassFilm film{{h.index, h.first_sample, h.samples}, std::vector<co_float4>(pixels), h.dropped, h.rays};
  std::memcpy(film.sums.data(), bytes.data() + sizeof(h), pixels * sizeof(co_float4));
  return film;
}

void send_film(const PassFilm& film, std::size_t pixels) {
  if (film.sums.size() != pixels) throw DeviceError("a partial film of the wrong size");
  std::vector<char> bytes(static_cast<std::size_t>(film_message_bytes(pixels)));
  const FilmHeader h{film.pass.index, film.pass.first_sample, film.pass.samples, 0, film.dropped, film.rays};
  std::memcpy(bytes.data(), &h, sizeof(h));
  std::memcpy(bytes.data() + sizeof(h), film.sums.data(), pixels * sizeof(co_float4));
  check(MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, 0, kFilm, MPI_COMM_WORLD),
        "MPI_Send of a partial film");
}

}  // namespace

void serve_passes(const MpiSession& mpi, PassJob& job, std::size_t pixels) {
  std::deque<int> waiting;  // ranks whose request waits for the window to open
  int told_to_stop = 0;
  AssignmentSends sends;
  while (!job.aborted() && !(told_to_stop == mpi.size() - 1 && job.finished() && sends.empty())) {
    bool busy = sends.reap();
    int flag = 0;
    MPI_Status status;
    check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status), "MPI_Iprobe");
    if (flag) {
      busy = true;
      if (status.MPI_TAG == kRequest) {
        int unused = 0;
        check(MPI_Recv(&unused, 1, MPI_INT, status.MPI_SOURCE, kRequest, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
              "MPI_Recv of a pass request");
        waiting.push_back(status.MPI_SOURCE);
      } else if (status.MPI_TAG == kFilm) {
        job.deliver(receive_film(status.MPI_SOURCE, pixels));
      } else {
        throw DeviceError(fmt::format("rank {} sent an unknown message (tag {})", status.MPI_SOURCE, status.MPI_TAG));
      }
    }
    while (!waiting.empty()) {
      SamplePass pass;
      const PassJob::Offer offer = job.try_next(pass);
      if (offer == PassJob::Offer::wait) break;
      sends.send(waiting.front(), offer == PassJob::Offer::pass ? &pass : nullptr);
      if (offer == PassJob::Offer::end) ++told_to_stop;
      waiting.pop_front();
      busy = true;
    }
    if (!busy) std::this_thread::sleep_for(kIdle);
  }
}

std::optional<SamplePass> AssignedPasses::next() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return aborted_ || ended_ || !assigned_.empty(); });
  if (aborted_ || assigned_.empty()) return std::nullopt;
  const SamplePass pass = assigned_.front();
  assigned_.pop_front();
  ++rendering_;
  changed_.notify_all();
  return pass;
}

void AssignedPasses::deliver(PassFilm film) {
  const std::lock_guard lock(mutex_);
  finished_.push_back(std::move(film));
  --rendering_;
  changed_.notify_all();
}

void AssignedPasses::abort() {
  const std::lock_guard lock(mutex_);
  aborted_ = true;
  changed_.notify_all();
}

void run_assigned_passes(AssignedPasses& passes, std::size_t pixels) {
  bool asked = false, ended = false;
  PixelList last_list;
  for (;;) {
    std::unique_lock lock(passes.mutex_);
    if (passes.aborted_) return;  // the failing device's exception is rethrown by DeviceWorkers::join
    if (ended && passes.assigned_.empty() && passes.rendering_ == 0 && passes.finished_.empty()) return;
    // one pass waiting per device keeps each busy across the round trip to rank 0
    const bool want = !ended && !asked && passes.assigned_.size() < passes.devices_;
    std::deque<PassFilm> to_send;
    to_send.swap(passes.finished_);
    lock.unlock();

    bool busy = !to_send.empty();
    for (const auto& film : to_send) send_film(film, pixels);
    if (want) {
      const int unused = 0;
      check(MPI_Send(&unused, 1, MPI_INT, 0, kRequest, MPI_COMM_WORLD), "MPI_Send of a pass request");
      asked = busy = true;
    }
    if (asked) {
      int flag = 0;
      MPI_Status status;
      check(MPI_Iprobe(0, kAssign, MPI_COMM_WORLD, &flag, &status), "MPI_Iprobe");
      if (flag) {
        int words = 0;
        check(MPI_Get_count(&status, MPI_UINT32_T, &words), "MPI_Get_count of a pass assignment");
        std::vector<std::uint32_t> message(static_cast<std::size_t>(std::max(words, 0)));
        check(MPI_Recv(message.data(), words, MPI_UINT32_T, 0, kAssign, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
              "MPI_Recv of a pass assignment");
        const SamplePass pass = read_assignment(message, last_list);
        asked = false;
        busy = true;
        const std::lock_guard relock(passes.mutex_);
        if (pass.samples == 0) {
          ended = passes.ended_ = true;
        } else {
          passes.assigned_.push_back(pass);
        }
        passes.changed_.notify_all();
      }
    }
    if (!busy) {
      std::unique_lock wait(passes.mutex_);
      passes.changed_.wait_for(wait, kIdle);
    }
  }
}

}  // namespace cohort
