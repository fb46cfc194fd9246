// Spreads the runs of a batch (a sweep's runs, the estimates `score` scores)
// over the ranks of an MPI job: `mpirun -n N touchcloud sweep ...`. Rank 0
// hands the next run to the next free rank (run times differ 10x between
// settings) and gets each finished run back as a serialised row; only rank 0
// writes outputs. Rank 0 computes too, between the messages: a thread of its
// own answers the other ranks, so `-n 2` has two ranks at work and no rank
// waits for rank 0 to finish a long run before it gets its next one.
//
// Without mpirun or srun (no MPI environment), or with one rank, every run
// runs here in order and MPI is never initialised: a plain run needs no MPI
// runtime. MPI stays inside this unit (mpi_dispatch.cpp); the build option
// TOUCHCLOUD_MPI turns it on.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace touchcloud::cli {

// Who ran a run: the MPI rank (0 alone) and the host name.
struct RunPlace {
  int rank = 0;
  std::string host;
};

// This process's rank as the launcher's environment tells it (0 without
// one); no MPI call. Ranks other than 0 leave reporting bad input to rank 0,
// which finds the same.
int launched_rank();

class RankTeam {
 public:
  // Runs job `index` on this rank; returns its row serialised. Must not throw:
  // a failing run is a row that records its error.
  using Work = std::function<std::string(std::size_t index)>;
  // On rank 0 only, once per finished run, one call at a time (any order).
  using Finished = std::function<void(std::size_t index, const RunPlace& place, const std::string& row)>;
  // Names a run in the message printed when the job is stopped ("setting 2 seed 11").
  using Describe = std::function<std::string(std::size_t index)>;

  // Joins the MPI job when launched by mpirun or srun (MPI_Init), else stands
  // alone as rank 0 of 1. InputError when launched on several ranks by a
  // build without MPI (each rank would run the whole batch).
  RankTeam();
  ~RankTeam();  // MPI_Finalize; on rank 0 before run() (bad input), it first tells the others to stop
  RankTeam(const RankTeam&) = delete;
  RankTeam& operator=(const RankTeam&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  const std::string& host() const { return host_; }
  // Ranks of this job on this host (1 alone): they share its cores.
  int ranks_on_host() const { return ranks_on_host_; }

  // Runs every job of `jobs` once, somewhere. Returns on rank 0 when all have
  // finished, on the others when none is left. Until then a signal that ends
  // the process (mpirun stops every rank when one dies) prints which runs
  // were lost, then `on_stop()` (what the output holds, how to resume).
  void run(const std::vector<std::size_t>& jobs, const Work& work, const Finished& finished,
           const Describe& describe, const std::function<std::string()>& on_stop);

 private:
  int rank_ = 0, size_ = 1, ranks_on_host_ = 1;
  bool mpi_ = false;
  bool ran_ = false;  // run() was reached: the other ranks were told to stop
  bool threads_ok_ = false;  // MPI calls from the dispatch thread are allowed
  std::string host_;
};

}  // namespace touchcloud::cli
