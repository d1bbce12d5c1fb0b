// `sweep` and `check` on MPI ranks (docs/scaling.md): `mpirun -n N shapebench sweep FILE
// --out DIR` needs no flag. Every rank loads the same sweep; rank 0 hands out chunks of
// point indices dynamically (guided: a quarter of the remaining points per compute thread
// of the run, at most 64, so the last chunks are single points and a slow point
// holds up one thread, not a rank) and computes on its own --jobs threads too; the other
// ranks send back each point's result bytes (a results.csv row as --jobs 1 writes it),
// and rank 0 writes them in point order through the same RunSweep (manifest, resume,
// lock) as a run without MPI. Rank 0 never blocks in MPI: it polls (MPI_Iprobe) between
// short waits, so its coordination costs no core of the run.
//
// MPI starts only when an MPI launcher started the process (OMPI_COMM_WORLD_SIZE,
// PMIX_RANK or PMI_RANK in the environment) and SHAPEBENCH_MPI is not 0; a plain run
// never calls MPI_Init. Ranks other than 0 print nothing (their stdout and stderr are
// /dev/null; a fatal error of theirs goes to the original stderr) and exit 0; the run's
// exit code is rank 0's. A rank that dies ends the run (mpirun stops the others): the
// rows written so far are kept and the same command, with or without mpirun, resumes.
// Built only when CMake finds MPI (SHAPEBENCH_HAVE_MPI); otherwise MpiRun does nothing.
#pragma once

#include <memory>

namespace shapebench::bench {

// Whether the environment says an MPI launcher started this process (and SHAPEBENCH_MPI
// is not "0"): what decides whether MpiRun initialises MPI.
bool LaunchedByMpiLauncher();

class MpiRun {
 public:
  // Initialises MPI (MPI_THREAD_FUNNELED) when LaunchedByMpiLauncher() and the build has
  // MPI, and installs the Distributor (bench/sweep/distribute.h) of this rank.
  MpiRun();
  ~MpiRun();  // Finish(0) when not finished
  MpiRun(const MpiRun&) = delete;
  MpiRun& operator=(const MpiRun&) = delete;

  // Ends MPI and returns the process' exit code: rank 0's `code` (an MPI_Abort of the
  // whole run when a distribution ended abnormally), 0 on the other ranks.
  int Finish(int code);

  class Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace shapebench::bench
