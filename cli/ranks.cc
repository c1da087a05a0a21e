#include "cli/ranks.h"

#include <cstdlib>
#include <stdexcept>

#ifdef MECHFLOW_MPI
// the C interface only: mpi.h would otherwise pull in the deprecated C++
// bindings, which need a library of their own
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace mechflow::cli {

#ifdef MECHFLOW_MPI

namespace {

bool LaunchedByMpirun() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

void Check(int code, const char* call) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string(call) + " failed");
}

}  // namespace

bool BuiltWithMpi() { return true; }

Ranks::Ranks() {
  if (!LaunchedByMpirun()) return;
  int provided = 0;
  Check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  mpi_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  MPI_Comm local;
  Check(MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &local),
        "MPI_Comm_split_type");
  MPI_Comm_size(local, &local_size_);
  MPI_Comm_free(&local);
}

Ranks::~Ranks() {
  if (mpi_) MPI_Finalize();
}

std::vector<std::string> Ranks::GatherToRoot(const std::string& mine) const {
  if (!mpi_) return {mine};
  // lengths first, then the bytes at their offsets
  int length = static_cast<int>(mine.size());
  std::vector<int> lengths(root() ? size_ : 0), offsets(root() ? size_ : 0);
  Check(MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Gather");
  std::string all;
  if (root()) {
    int total = 0;
    for (int r = 0; r < size_; ++r) offsets[r] = total, total += lengths[r];
    all.resize(total);
  }
  Check(MPI_Gatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0,
                    MPI_COMM_WORLD),
        "MPI_Gatherv");
  std::vector<std::string> parts;
  for (int r = 0; root() && r < size_; ++r) parts.push_back(all.substr(offsets[r], lengths[r]));
  return parts;
}

std::vector<std::string> Ranks::AllGather(const std::string& mine) const {
  if (!mpi_) return {mine};
  int length = static_cast<int>(mine.size());
  std::vector<int> lengths(size_), offsets(size_);
  Check(MPI_Allgather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, MPI_COMM_WORLD), "MPI_Allgather");
  int total = 0;
  for (int r = 0; r < size_; ++r) offsets[r] = total, total += lengths[r];
  std::string all(total, '\0');
  Check(MPI_Allgatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR,
                       MPI_COMM_WORLD),
        "MPI_Allgatherv");
  std::vector<std::string> parts;
  for (int r = 0; r < size_; ++r) parts.push_back(all.substr(offsets[r], lengths[r]));
  return parts;
}

int Ranks::Max(int value) const {
  if (!mpi_) return value;
  int result = value;
  Check(MPI_Allreduce(&value, &result, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD), "MPI_Allreduce");
  return result;
}

#else  // one process, no MPI

bool BuiltWithMpi() { return false; }

Ranks::Ranks() {
  // started by mpirun with several processes, each would run the whole sweep
  // and overwrite the others' files
  const char* size = std::getenv("OMPI_COMM_WORLD_SIZE");
  if (size && std::atoi(size) > 1)
    throw std::runtime_error("this mechflow was built without MPI (configure with -DMECHFLOW_MPI=ON to run a sweep "
                             "under mpirun)");
}

Ranks::~Ranks() = default;
std::vector<std::string> Ranks::GatherToRoot(const std::string& mine) const { return {mine}; }
std::vector<std::string> Ranks::AllGather(const std::string& mine) const { return {mine}; }
int Ranks::Max(int value) const { return value; }

#endif

}  // namespace mechflow::cli
