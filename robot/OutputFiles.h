#pragma once
// Files a command writes. Each goes to a temporary name in its own folder, every write and the
// close are checked, and it is renamed into place when complete, so a reader never sees half a
// file. While an OutputTransaction is open (apps/main.cpp opens one per command) the renames
// wait for commit(): a run that fails leaves none of its files and none of the folders it made.
// A path that exists and is not a regular file (/dev/stdout, /dev/full, a FIFO) is written in
// place: renaming over it would replace the device.
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace nao::io {

// Throws nao::RunFailure(path, ...) when the file cannot be created, written or closed.
void writeFile(const std::string& path, std::string_view bytes);

// For writers that insist on a file name of their own (OpenCV's model files): `write` gets a
// temporary path in the same folder and must leave a complete file there.
void writeFileWith(const std::string& path, const std::function<void(const std::string& tempPath)>& write);

// Creates `dir` and its missing parents. Inside a transaction, the folders it created are
// removed again (if empty) when the transaction is discarded.
void makeDirectories(const std::string& dir);

// Why `path` cannot be written as an output file (empty if it can): checked before a run starts.
std::string outputFileProblem(const std::string& path);
// Why `dir` cannot serve as an output folder (it exists as a writable folder, or its nearest
// existing ancestor is a writable folder): empty if it can.
std::string outputDirectoryProblem(const std::string& dir);

class OutputTransaction {
 public:
  OutputTransaction();
  ~OutputTransaction();  // discards what was not committed
  OutputTransaction(const OutputTransaction&) = delete;
  OutputTransaction& operator=(const OutputTransaction&) = delete;

  // Renames every staged file into place. Throws nao::RunFailure naming a file that failed.
  void commit();
  // Removes the staged files and the folders made for them.
  void discard();
  // Discards too when the process is interrupted (SIGINT, SIGTERM, SIGHUP), then dies of the
  // signal as it would have. A handler installed later (the NAO backend's soft stop) wins.
  void discardOnSignals();

 private:
  friend struct TransactionAccess;
  struct Staged {
    std::string temp, path;
  };
  std::vector<Staged> staged_;
  std::vector<std::string> madeDirectories_;
};

}  // namespace nao::io
