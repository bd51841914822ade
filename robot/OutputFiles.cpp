#include "robot/OutputFiles.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cerrno>
#include <climits>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "robot/Error.h"

namespace nao::io {

namespace fs = std::filesystem;

struct TransactionAccess {
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  static OutputTransaction*& open() {
    static OutputTransaction* t = nullptr;
    return t;
  }
  static std::vector<OutputTransaction::Staged>& staged(OutputTransaction& t) { return t.staged_; }
  static std::vector<std::string>& made(OutputTransaction& t) { return t.madeDirectories_; }
};

namespace {

std::string errnoText() { return std::strerror(errno); }

// ".name.tmp-PID-N.ext" beside `path`: hidden, unique, and with the same extension (OpenCV
// chooses a model file's format by it).
std::string tempPathFor(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  const fs::path p(path);
  std::string name(".");  // appended piece by piece: GCC 12 warns falsely on "." + string
  name += p.stem().string();
  name += ".tmp-";
  name += std::to_string(::getpid());
  name += '-';
  name += std::to_string(counter++);
  name += p.extension().string();
  return (p.parent_path() / name).string();
}

std::string folderOf(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? "." : parent.string();
}

bool isSpecialFile(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode);
}

void writeAll(int fd, std::string_view bytes, const std::string& path) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw RunFailure(path, "write failed: " + (n < 0 ? errnoText() : std::string("no progress")));
    done += static_cast<std::size_t>(n);
  }
}

// Hands a complete temporary file over: renamed now, or at the open transaction's commit.
void finish(const std::string& temp, const std::string& path) {
  std::lock_guard<std::mutex> lock(TransactionAccess::mutex());
  if (OutputTransaction* t = TransactionAccess::open()) {
    auto& staged = TransactionAccess::staged(*t);
    for (auto& s : staged)
      if (s.path == path) {  // written again in the same run: the newer file wins
        ::unlink(s.temp.c_str());
        s.temp = temp;
        return;
      }
    staged.push_back({temp, path});
    return;
  }
  if (::rename(temp.c_str(), path.c_str()) != 0) {
    const std::string why = errnoText();
    ::unlink(temp.c_str());
    throw RunFailure(path, "cannot rename into place: " + why);
  }
}

// Temporary files being written and not yet staged: a signal arriving during a write (the
// fsync may take long on a busy disk) removes them too. Fixed slots, claimed with atomics, so
// the signal handler reads them without a lock or an allocation; more writers at once than
// slots go unregistered (and may leave their file when interrupted, as before).
struct InFlightSlot {
  std::atomic<bool> claimed{false};
  std::atomic<bool> ready{false};
  char path[PATH_MAX] = {};
};
InFlightSlot inFlight[32];

// Registers `temp` for the length of one write.
class InFlight {
 public:
  explicit InFlight(const std::string& temp) {
    if (temp.size() >= PATH_MAX) return;
    for (auto& s : inFlight) {
      bool expected = false;
      if (!s.claimed.compare_exchange_strong(expected, true)) continue;
      std::memcpy(s.path, temp.c_str(), temp.size() + 1);
      s.ready.store(true);
      slot_ = &s;
      return;
    }
  }
  ~InFlight() {
    if (!slot_) return;
    slot_->ready.store(false);
    slot_->claimed.store(false);
  }
  InFlight(const InFlight&) = delete;
  InFlight& operator=(const InFlight&) = delete;

 private:
  InFlightSlot* slot_ = nullptr;
};

}  // namespace

void writeFile(const std::string& path, std::string_view bytes) {
  if (path.empty()) throw RunFailure("output", "empty file name");
  if (isSpecialFile(path)) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) throw RunFailure(path, "cannot open for writing: " + errnoText());
    try {
      writeAll(fd, bytes, path);
    } catch (...) {
      ::close(fd);
      throw;
    }
    if (::close(fd) != 0) throw RunFailure(path, "write failed: " + errnoText());
    return;
  }
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw RunFailure(path, "is a folder, not a file");
  const std::string temp = tempPathFor(path);
  const InFlight registered(temp);  // before the file exists: no moment it is unknown
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) throw RunFailure(path, "cannot create in " + folderOf(path) + ": " + errnoText());
  try {
    writeAll(fd, bytes, path);
    // A full disk may only show when the data reaches it.
    if (::fsync(fd) != 0 && errno != EINVAL) throw RunFailure(path, "write failed: " + errnoText());
  } catch (...) {
    ::close(fd);
    ::unlink(temp.c_str());
    throw;
  }
  if (::close(fd) != 0) {
    const std::string why = errnoText();
    ::unlink(temp.c_str());
    throw RunFailure(path, "write failed: " + why);
  }
  finish(temp, path);
}

void writeFileWith(const std::string& path, const std::function<void(const std::string& tempPath)>& write) {
  if (path.empty()) throw RunFailure("output", "empty file name");
  const std::string temp = tempPathFor(path);
  const InFlight registered(temp);
  try {
    write(temp);
  } catch (...) {
    ::unlink(temp.c_str());
    throw;
  }
  struct stat st {};
  if (::stat(temp.c_str(), &st) != 0 || !S_ISREG(st.st_mode) || st.st_size == 0) {
    ::unlink(temp.c_str());
    throw RunFailure(path, "write failed (nothing was written)");
  }
  finish(temp, path);
}

void makeDirectories(const std::string& dir) {
  if (dir.empty()) throw RunFailure("output", "empty folder name");
  fs::path sofar;
  for (const auto& part : fs::path(dir)) {
    sofar /= part;
    std::error_code ec;
    if (fs::is_directory(sofar, ec)) continue;
    if (fs::exists(sofar, ec)) throw RunFailure(sofar.string(), "exists and is not a folder");
    // Listed before it is made, so an interrupt right after the mkdir removes it too.
    std::lock_guard<std::mutex> lock(TransactionAccess::mutex());
    OutputTransaction* t = TransactionAccess::open();
    if (t) TransactionAccess::made(*t).push_back(sofar.string());
    if (::mkdir(sofar.c_str(), 0777) != 0) {
      const int err = errno;
      if (t) TransactionAccess::made(*t).pop_back();  // not ours (made meanwhile) or not made
      if (err != EEXIST) throw RunFailure(sofar.string(), "cannot create the folder: " + std::string(std::strerror(err)));
    }
  }
}

std::string outputFileProblem(const std::string& path) {
  if (path.empty()) return "an empty file name";
  if (fs::path(path).filename().string().size() > NAME_MAX) return "file name too long";
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (fs::is_directory(status)) return "is a folder, not a file";
  if (fs::exists(status) && !fs::is_regular_file(status))
    return ::access(path.c_str(), W_OK) == 0 ? "" : "cannot be written (" + errnoText() + ")";
  const std::string folder = folderOf(path);
  const auto folderStatus = fs::status(folder, ec);
  if (!fs::exists(folderStatus)) return "its folder " + folder + " does not exist";
  if (!fs::is_directory(folderStatus)) return folder + " is not a folder";
  if (::access(folder.c_str(), W_OK | X_OK) != 0) return "its folder " + folder + " is not writable (" + errnoText() + ")";
  return "";
}

std::string outputDirectoryProblem(const std::string& dir) {
  if (dir.empty()) return "an empty folder name";
  fs::path p(dir);
  std::error_code ec;
  // The folder itself, or the nearest ancestor that exists (the rest will be made).
  while (!fs::exists(p, ec)) {
    if (!p.has_parent_path() || p.parent_path() == p) {
      p = ".";
      break;
    }
    p = p.parent_path();
    if (p.empty()) p = ".";
  }
  if (!fs::is_directory(p, ec)) return p.string() + " exists and is not a folder";
  if (::access(p.c_str(), W_OK | X_OK) != 0) return p.string() + " is not writable (" + errnoText() + ")";
  return "";
}

namespace {

// Only async-signal-safe calls: unlink, rmdir, signal, raise. The interrupted thread may have
// been changing the lists; at worst a file is left, never a wrong one removed.
void discardAndDie(int sig) {
  for (const auto& s : inFlight)
    if (s.ready.load()) ::unlink(s.path);
  if (OutputTransaction* t = TransactionAccess::open()) {
    for (const auto& s : TransactionAccess::staged(*t)) ::unlink(s.temp.c_str());
    const auto& made = TransactionAccess::made(*t);
    for (auto it = made.rbegin(); it != made.rend(); ++it) ::rmdir(it->c_str());
  }
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

}  // namespace

void OutputTransaction::discardOnSignals() {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) std::signal(sig, discardAndDie);
}

OutputTransaction::OutputTransaction() {
  std::lock_guard<std::mutex> lock(TransactionAccess::mutex());
  if (TransactionAccess::open()) throw std::logic_error("OutputTransaction: one is open already");
  TransactionAccess::open() = this;
}

OutputTransaction::~OutputTransaction() {
  discard();
  std::lock_guard<std::mutex> lock(TransactionAccess::mutex());
  if (TransactionAccess::open() == this) TransactionAccess::open() = nullptr;
}

void OutputTransaction::commit() {
  std::lock_guard<std::mutex> lock(TransactionAccess::mutex());
  while (!staged_.empty()) {
    const Staged s = staged_.front();
    if (::rename(s.temp.c_str(), s.path.c_str()) != 0)
      throw RunFailure(s.path, "cannot rename into place: " + errnoText());
    staged_.erase(staged_.begin());
  }
  madeDirectories_.clear();
}

void OutputTransaction::discard() {
  std::lock_guard<std::mutex> lock(TransactionAccess::mutex());
  for (const auto& s : staged_) ::unlink(s.temp.c_str());
  staged_.clear();
  for (auto it = madeDirectories_.rbegin(); it != madeDirectories_.rend(); ++it) ::rmdir(it->c_str());
  madeDirectories_.clear();
}

}  // namespace nao::io
