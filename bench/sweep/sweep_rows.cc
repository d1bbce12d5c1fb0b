#include "bench/sweep/sweep_rows.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "common/csv.h"

namespace shapebench::bench {
namespace {

namespace fs = std::filesystem;

void WriteRowText(std::FILE* file, const std::string& text, const fs::path& path) {
  if (std::fwrite(text.data(), 1, text.size(), file) != text.size()) {
    throw std::runtime_error("cannot write " + path.string() + ": " + std::strerror(errno));
  }
}

}  // namespace

SweepRows::SweepRows(const fs::path& dir, const std::vector<std::string>& columns, std::future<ResumedRows>* ready,
                     Durability durability, const std::vector<std::uint64_t>& ahead_on_disk)
    : partial_path_(dir / kSweepPartialFile), ahead_path_(dir / kSweepAheadFile), header_(CsvRecord(columns)),
      ready_(ready), durability_(durability), ahead_rows_(ahead_on_disk.begin(), ahead_on_disk.end()) {}

SweepRows::~SweepRows() {
  StopFlusher();
  if (partial_ != nullptr) std::fclose(partial_);
  if (ahead_ != nullptr) std::fclose(ahead_);
}

void SweepRows::Fail(const fs::path& path) {
  throw std::runtime_error("cannot write " + path.string() + ": " + std::strerror(errno));
}

bool SweepRows::Prepared(bool wait) {
  if (failure_) std::rethrow_exception(failure_);
  if (!ready_->valid()) return true;
  if (!wait && ready_->wait_for(std::chrono::seconds(0)) == std::future_status::timeout) return false;
  unprepared_ = true;
  try {
    ready_->get();  // a deferred one runs here
  } catch (...) {
    failure_ = std::current_exception();
    throw;
  }
  unprepared_ = false;
  return true;
}

void SweepRows::OpenPartial() {
  partial_ = std::fopen(partial_path_.c_str(), "ab");
  if (partial_ == nullptr) Fail(partial_path_);
  if (!waiting_.empty()) WriteRowText(partial_, waiting_, partial_path_);
  waiting_.clear();
  dirty_ = true;
}

void SweepRows::OpenAhead() {
  std::error_code ec;
  const bool empty = !fs::exists(ahead_path_, ec) || fs::file_size(ahead_path_, ec) == 0;
  ahead_ = std::fopen(ahead_path_.c_str(), "ab");
  if (ahead_ == nullptr) Fail(ahead_path_);
  if (empty) WriteRowText(ahead_, header_, ahead_path_);
}

void SweepRows::ThrowIfFailed() const {
  if (failure_) std::rethrow_exception(failure_);
}

void SweepRows::OpenIfReady() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!ready_->valid()) OpenPartial();
}

void SweepRows::Add(std::uint64_t k, const std::string& row) {
  std::lock_guard<std::mutex> lock(mutex_);
  ThrowIfFailed();
  StartFlusherIfDue();
  next_ = k + 1;
  if (!ahead_rows_.empty()) ahead_rows_.erase(k);
  if (partial_ == nullptr && !Prepared(false)) {
    waiting_ += row;
    return;
  }
  if (partial_ == nullptr) OpenPartial();
  WriteRowText(partial_, row, partial_path_);
  dirty_ = true;
}

void SweepRows::Ahead(std::uint64_t k, const std::string& row) {
  std::lock_guard<std::mutex> lock(mutex_);
  ThrowIfFailed();
  if (k < next_ || ahead_rows_.count(k) > 0) return;  // its turn came, or written ahead already
  StartFlusherIfDue();
  Prepared(true);
  if (ahead_ == nullptr) OpenAhead();
  WriteRowText(ahead_, row, ahead_path_);
  ahead_rows_.insert(k);
  dirty_ = true;
}

std::uint64_t SweepRows::WaitingAhead() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return ahead_rows_.size();
}

void SweepRows::StartFlusherIfDue() {
  if (flusher_.joinable() || stopping_ || std::chrono::steady_clock::now() - started_ < kFlushEvery) return;
  flusher_ = std::thread([this] { FlushLoop(); });  // it waits for mutex_, held here
}

void SweepRows::FlushLoop() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_flusher_.wait_for(lock, kFlushEvery, [&] { return stopping_; })) {
    try {
      if (partial_ == nullptr && !waiting_.empty() && Prepared(false)) OpenPartial();
      if (!dirty_) continue;
      if (partial_ != nullptr && std::fflush(partial_) != 0) Fail(partial_path_);
      if (ahead_ != nullptr && std::fflush(ahead_) != 0) Fail(ahead_path_);
      dirty_ = false;
    } catch (...) {
      if (!failure_) failure_ = std::current_exception();  // thrown by the next Add or Close
      return;
    }
  }
}

void SweepRows::StopFlusher() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  stop_flusher_.notify_all();
  if (flusher_.joinable()) flusher_.join();
}

void SweepRows::Close() {
  StopFlusher();
  std::lock_guard<std::mutex> lock(mutex_);
  ThrowIfFailed();
  if (partial_ == nullptr) {  // rows still waiting, or none (interrupted before the first)
    Prepared(true);
    OpenPartial();
  }
  for (std::FILE** file : {&partial_, &ahead_}) {
    if (*file == nullptr) continue;
    const fs::path& path = file == &partial_ ? partial_path_ : ahead_path_;
    if (std::fflush(*file) != 0) Fail(path);
    if (durability_ == Durability::kSynced && !SyncFile(fileno(*file))) Fail(path);
    std::FILE* closing = *file;
    *file = nullptr;
    if (std::fclose(closing) != 0) Fail(path);
  }
}

void SweepRows::KeepComputed() noexcept {
  StopFlusher();
  std::lock_guard<std::mutex> lock(mutex_);
  try {
    if (partial_ == nullptr && !waiting_.empty() && !unprepared_ && !failure_) {
      Prepared(true);
      OpenPartial();
    }
  } catch (...) {
  }
  if (ready_->valid()) ready_->wait();  // it reads the caller's variables
}

}  // namespace shapebench::bench
