#pragma once
// `nao-soccer batch`: one evaluation with rows (eval challenge, match, localization) split into
// chunks of seeds, each chunk one task `nao-soccer eval ... --seeds LIST --rows DIR/chunk-K.jsonl`
// on a runner; the rows merged and aggregated by the evaluation itself
// (`eval ... --rows DIR/rows.jsonl`, nothing left to run), so the aggregate is the one a single
// uninterrupted run gives, whichever runner and chunking. The batch folder keeps everything a
// later `--resume` needs: the plan, the rows and log of each chunk.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace nao::cli {

// What a batch runs. Saved as DIR/batch.json; --resume continues only the same plan.
struct BatchPlan {
  std::string eval;                   // "eval challenge"
  std::vector<std::string> evalArgs;  // the evaluation's options as given (after "eval TARGET")
  std::vector<std::uint64_t> seeds;   // in the evaluation's order
  int chunkSize = 1;

  std::vector<std::vector<std::uint64_t>> chunks() const;
  nlohmann::json toJson() const;
  // Throws nao::Error(path, ...) for a file that is not a plan.
  static BatchPlan fromJson(const nlohmann::json& j, const std::string& path);
};

// "1-3,7": the seeds as --seeds takes them, runs of consecutive seeds as ranges.
std::string seedListText(const std::vector<std::uint64_t>& seeds);

// A chunk's rows file, read strictly and left as it is.
struct ChunkRows {
  std::map<std::uint64_t, nlohmann::json> rows;  // the complete rows, by seed
  std::vector<std::uint64_t> missing;             // the chunk's seeds without a row
  bool truncatedTail = false;                     // a last line cut short (its task was stopped while writing)
};
// Throws nao::Error(path, "line N: ...") for a line that is neither a row of one of `seeds` nor
// a cut-short last line, and for a seed twice: such a file is never merged.
ChunkRows readChunkRows(const std::string& path, const std::vector<std::uint64_t>& seeds);

// One task: the chunk's evaluation, its output (stdout and stderr) appended to `log`.
struct BatchTask {
  std::size_t chunk = 0;
  std::vector<std::string> argv;
  std::string log;
};

class BatchRunner {
 public:
  virtual ~BatchRunner() = default;
  // Starts (or submits) the tasks. Throws nao::RunFailure when the runner refuses them.
  virtual void start(const std::vector<BatchTask>& tasks) = 0;
  // Polls: true while any task still runs or waits.
  virtual bool busy() = 0;
  // Stops every task of this runner (interrupted batch) and waits until they ended.
  virtual void cancel() = 0;
  // The exit status of each task the runner knows it of (slurm without accounting: none).
  virtual std::map<std::size_t, int> exitStatuses() const = 0;
};

// "local" (processes here), "parallel" (GNU parallel; sshlogin: its --sshlogin) or "slurm" (one
// sbatch job array per MaxArraySize tasks, named after the batch folder). Throws nao::RunFailure
// when the engine is missing or not answering (sbatch not installed, no Slurm controller).
std::unique_ptr<BatchRunner> makeBatchRunner(const std::string& runner, int jobs, const std::string& sshlogin,
                                             const std::string& dir);

// A shell word for `s` (single quotes).
std::string shellQuote(const std::string& s);

}  // namespace nao::cli
