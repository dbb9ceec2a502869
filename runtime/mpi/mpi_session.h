// MPI for one `cohort render` job: initialised only when an MPI launcher (mpirun, srun) started the
// process, so a plain run never touches MPI. Only the thread that made the session calls MPI.
#pragma once

#include <string>
#include <vector>

namespace cohort {

class MpiSession {
 public:
  static bool launched_by_mpi();  // the launcher's environment: Open MPI, PMIx or PMI

  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  int local_rank() const { return local_rank_; }  // among the ranks on this machine
  const std::string& host() const { return host_; }

  // Prints "cohort: rank R of N on HOST: message" and ends every rank of the job with `code`.
  [[noreturn]] void abort(const std::string& message, int code) const;

  // Rank 0 gets every rank's text in rank order; the others get an empty vector.
  std::vector<std::string> gather(const std::string& text) const;

 private:
  int rank_ = 0;
  int size_ = 1;
  int local_rank_ = 0;
  std::string host_;
};

}  // namespace cohort
