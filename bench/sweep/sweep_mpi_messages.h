// The messages between MPI ranks of a distribution (bench/sweep/sweep_mpi.h): their tags
// and byte layout (64-bit words), and the non-blocking receive both sides poll with.
// Included by sweep_mpi.cc and sweep_mpi_worker.h only, inside SHAPEBENCH_HAVE_MPI.
#pragma once

#ifndef OMPI_SKIP_MPICXX
#define OMPI_SKIP_MPICXX 1
#endif
#ifndef MPICH_SKIP_MPICXX
#define MPICH_SKIP_MPICXX 1
#endif
#include <mpi.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

namespace shapebench::bench::mpi {

// Messages: a worker's hello (its threads) and results to rank 0; chunks, the end of a
// distribution (stop) and of the run (quit) from rank 0.
enum Tag : int { kHello = 1, kResult = 2, kChunk = 3, kStop = 4, kQuit = 5 };
inline constexpr std::uint64_t kMaxChunk = 64;
inline constexpr auto kPoll = std::chrono::microseconds(500);  // between MPI_Iprobe calls when idle

inline void PutU64(std::string* bytes, std::uint64_t value) {
  bytes->append(reinterpret_cast<const char*>(&value), sizeof value);
}

inline std::uint64_t GetU64(const std::string& bytes, std::size_t* at) {
  std::uint64_t value = 0;
  if (*at + sizeof value > bytes.size()) throw std::runtime_error("MPI: a message arrived cut short");
  std::memcpy(&value, bytes.data() + *at, sizeof value);
  *at += sizeof value;
  return value;
}

inline void Send(const std::string& bytes, int to, int tag) {
  MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD);
}

// The message MPI_Iprobe found from `from` (MPI_ANY_SOURCE: any), if any: *tag, *source set.
inline bool ReceiveAny(int from, std::string* bytes, int* tag, int* source) {
  int flag = 0;
  MPI_Status status;
  MPI_Iprobe(from, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
  if (flag == 0) return false;
  int count = 0;
  MPI_Get_count(&status, MPI_BYTE, &count);
  bytes->assign(static_cast<std::size_t>(count), '\0');
  MPI_Recv(bytes->data(), count, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
           MPI_STATUS_IGNORE);
  *tag = status.MPI_TAG;
  *source = status.MPI_SOURCE;
  return true;
}

}  // namespace shapebench::bench::mpi
