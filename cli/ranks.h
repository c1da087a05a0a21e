#pragma once
// Ranks: the processes of one `mechflow sweep` or `mechflow fit`. Started by mpirun (and built
// with MECHFLOW_MPI) they are the MPI ranks of MPI_COMM_WORLD; otherwise there
// is one rank and nothing is exchanged, so a plain `mechflow sweep` neither
// needs nor starts MPI.
//
// MPI is initialised only when the launcher's environment says the process is
// one of several started together (OMPI_COMM_WORLD_SIZE, PMIX_RANK, PMI_RANK):
// a singleton MPI_Init would try to start OpenMPI's runtime for nothing. MPI
// calls come from the constructing thread only (MPI_THREAD_FUNNELED); the
// sweep's worker threads never call MPI.

#include <string>
#include <vector>

namespace mechflow::cli {

class Ranks {
 public:
  Ranks();   // MPI_Init_thread when launched by mpirun
  ~Ranks();  // MPI_Finalize when initialised
  Ranks(const Ranks&) = delete;
  Ranks& operator=(const Ranks&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  // Ranks sharing this machine (for the default number of threads per rank).
  int local_size() const { return local_size_; }
  bool root() const { return rank_ == 0; }

  // Collective: every rank passes its bytes; rank 0 gets all of them in rank
  // order, the other ranks an empty list.
  std::vector<std::string> GatherToRoot(const std::string& mine) const;
  // Collective: every rank passes its bytes and gets everyone's, in rank order.
  std::vector<std::string> AllGather(const std::string& mine) const;
  // Collective: the largest `value` over the ranks, on every rank.
  int Max(int value) const;

 private:
  bool mpi_ = false;
  int rank_ = 0, size_ = 1, local_size_ = 1;
};

// True when this mechflow was built with MPI.
bool BuiltWithMpi();

}  // namespace mechflow::cli
