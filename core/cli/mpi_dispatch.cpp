#include "mpi_dispatch.hpp"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <mutex>
#include <thread>

#if TOUCHCLOUD_WITH_MPI
// The C API only: no C++ bindings (deprecated, and noisy under -Wextra).
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

#include "touchcloud/error.hpp"
#include "touchcloud/interrupt_cleanup.hpp"

namespace touchcloud::cli {

namespace {

// The first of these the launcher set: Open MPI's mpirun, then PMIx and PMI
// (srun, MPICH's launchers).
int env_number(std::initializer_list<const char*> names, int otherwise) {
  for (const char* n : names)
    if (const char* v = std::getenv(n); v && *v) return std::atoi(v);
  return otherwise;
}

int launched_size() { return env_number({"OMPI_COMM_WORLD_SIZE", "PMIX_SIZE", "PMI_SIZE", "SLURM_NTASKS"}, 1); }
bool launched() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMIX_RANK") || std::getenv("PMI_RANK");
}

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

// The runs in flight, for the message a stopping signal prints.
class LostRuns {
 public:
  LostRuns(const RankTeam::Describe& describe, const std::function<std::string()>& on_stop, std::size_t total)
      : describe_(describe), on_stop_(on_stop), total_(total) {}
  ~LostRuns() { say_on_interrupt(""); }
  void started(std::size_t job, const RunPlace& place) {
    std::lock_guard lock(mutex_);
    running_[job] = place;
    update();
  }
  void finished(std::size_t job) {
    std::lock_guard lock(mutex_);
    running_.erase(job);
    ++done_;
    update();
  }

 private:
  void update() {
    std::string text = "touchcloud: error: stopped with " + std::to_string(total_ - done_) + " of " +
                       std::to_string(total_) + " runs not finished";
    if (!running_.empty()) {
      text += "; lost while running:";
      for (const auto& [job, place] : running_)
        text += " " + describe_(job) + " (rank " + std::to_string(place.rank) + ", " + place.host + ");";
      text.pop_back();
    }
    say_on_interrupt(text + "; " + on_stop_());
  }

  const RankTeam::Describe& describe_;
  const std::function<std::string()>& on_stop_;
  std::size_t total_, done_ = 0;
  std::map<std::size_t, RunPlace> running_;
  std::mutex mutex_;
};

#if TOUCHCLOUD_WITH_MPI
enum Tag : int { kReady = 1, kResult = 2, kJob = 3, kStop = 4 };

void check(int status, const char* what) {
  if (status != MPI_SUCCESS) throw RunError(std::string("MPI: ") + what + " failed");
}

// Worker ranks: say ready (with the host name), then run what rank 0 sends
// until it says stop. A result is [job index: 8 bytes][row].
void serve(const RankTeam::Work& work, const std::string& host) {
  check(MPI_Send(host.data(), static_cast<int>(host.size()), MPI_CHAR, 0, kReady, MPI_COMM_WORLD), "send");
  for (;;) {
    std::uint64_t job = 0;
    MPI_Status status;
    check(MPI_Recv(&job, 1, MPI_UINT64_T, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &status), "receive");
    if (status.MPI_TAG == kStop) return;
    const std::string row = work(job);
    std::string message(sizeof job, '\0');
    std::memcpy(message.data(), &job, sizeof job);
    message += row;
    check(MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, kResult, MPI_COMM_WORLD), "send");
  }
}

// Rank 0's dispatch thread: answers every other rank until each was told to
// stop and has returned its last result. Polls (MPI_Iprobe, then a short
// sleep): a blocking receive would spin on a core rank 0's own runs need.
void dispatch(int size, std::atomic<std::size_t>& next, const std::vector<std::size_t>& jobs,
              const std::function<void(std::size_t, const RunPlace&, const std::string&)>& finished,
              LostRuns& lost, const std::atomic<bool>& failed) {
  std::map<int, RunPlace> places;
  int working = size - 1;
  while (working > 0) {
    int flag = 0;
    MPI_Status status;
    check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status), "probe");
    if (!flag) {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      continue;
    }
    int bytes = 0;
    MPI_Get_count(&status, MPI_CHAR, &bytes);
    std::string message(static_cast<std::size_t>(bytes), '\0');
    check(MPI_Recv(message.data(), bytes, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
                   MPI_STATUS_IGNORE), "receive");
    const int from = status.MPI_SOURCE;
    if (status.MPI_TAG == kReady) {
      places[from] = RunPlace{from, message};
    } else {
      std::uint64_t job = 0;
      std::memcpy(&job, message.data(), sizeof job);
      finished(job, places[from], message.substr(sizeof job));
      lost.finished(job);
    }
    const std::size_t i = failed ? jobs.size() : next++;
    if (i < jobs.size()) {
      const std::uint64_t job = jobs[i];
      lost.started(job, places[from]);
      check(MPI_Send(&job, 1, MPI_UINT64_T, from, kJob, MPI_COMM_WORLD), "send");
    } else {
      const std::uint64_t none = 0;
      check(MPI_Send(&none, 1, MPI_UINT64_T, from, kStop, MPI_COMM_WORLD), "send");
      --working;
    }
  }
}
#endif

}  // namespace

int launched_rank() { return env_number({"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"}, 0); }

RankTeam::RankTeam() : host_(host_name()) {
  if (!launched() || launched_size() <= 1) return;
#if TOUCHCLOUD_WITH_MPI
  // Rank 0's dispatch thread makes every MPI call while the main thread
  // runs; MPI_THREAD_SERIALIZED allows that.
  int provided = 0;
  check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided), "MPI_Init_thread");
  mpi_ = true;
  threads_ok_ = provided >= MPI_THREAD_SERIALIZED;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  MPI_Comm host_comm;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &host_comm);
  MPI_Comm_size(host_comm, &ranks_on_host_);
  MPI_Comm_free(&host_comm);
#else
  if (launched_rank() == 0)
    throw InputError("launched on " + std::to_string(launched_size()) +
                     " MPI ranks, but this touchcloud was built without MPI (cmake -DTOUCHCLOUD_MPI=ON, "
                     "with libopenmpi-dev): every rank would run the whole batch");
  throw InputError("built without MPI");
#endif
}

RankTeam::~RankTeam() {
#if TOUCHCLOUD_WITH_MPI
  if (!mpi_) return;
  if (rank_ == 0 && !ran_)
    for (int r = 1; r < size_; ++r) {
      const std::uint64_t none = 0;
      MPI_Send(&none, 1, MPI_UINT64_T, r, kStop, MPI_COMM_WORLD);
    }
  MPI_Finalize();
#endif
}

void RankTeam::run(const std::vector<std::size_t>& jobs, const Work& work, const Finished& finished,
                   const Describe& describe, const std::function<std::string()>& on_stop) {
  ran_ = true;
#if TOUCHCLOUD_WITH_MPI
  if (mpi_ && rank_ != 0) return serve(work, host_);
#endif
  LostRuns lost(describe, on_stop, jobs.size());
  // A failing `finished` (a full disk) ends the batch once the runs under way are in.
  std::mutex finished_mutex;
  std::exception_ptr failure;
  std::atomic<bool> failed{false};
  const auto finish = [&](std::size_t job, const RunPlace& place, const std::string& row) {
    std::lock_guard lock(finished_mutex);
    if (failure) return;
    try {
      finished(job, place, row);
    } catch (...) {
      failure = std::current_exception();
      failed = true;
    }
  };
  std::atomic<std::size_t> next{0};
  std::thread dispatcher;
#if TOUCHCLOUD_WITH_MPI
  if (mpi_) {
    if (!threads_ok_) {  // rank 0 only dispatches
      dispatch(size_, next, jobs, finish, lost, failed);
      if (failure) std::rethrow_exception(failure);
      return;
    }
    dispatcher = std::thread([&] { dispatch(size_, next, jobs, finish, lost, failed); });
  }
#endif
  const RunPlace here{rank_, host_};
  try {
    for (std::size_t i; !failed && (i = next++) < jobs.size();) {
      lost.started(jobs[i], here);
      const std::string row = work(jobs[i]);
      finish(jobs[i], here, row);
      lost.finished(jobs[i]);
    }
  } catch (...) {
    if (dispatcher.joinable()) dispatcher.join();
    throw;
  }
  if (dispatcher.joinable()) dispatcher.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace touchcloud::cli
