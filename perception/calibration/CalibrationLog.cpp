#include "perception/calibration/CalibrationLog.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "robot/Error.h"

namespace nao::calibration {
namespace {

constexpr std::string_view kMagic = "NAOCALLOG\n";
constexpr int kFormat = 1;
constexpr std::uint32_t kMaxJson = 1 << 20;                   // a record's JSON is a few hundred bytes
constexpr std::uint32_t kMaxPayload = 8192u * 8192u * 2u;     // the largest image the decoders take

void putU32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

void putChunk(std::string& out, const nlohmann::json& j, std::string_view payload = {}) {
  const std::string text = j.dump();
  putU32(out, static_cast<std::uint32_t>(text.size()));
  out += text;
  putU32(out, static_cast<std::uint32_t>(payload.size()));
  out.append(payload.data(), payload.size());
}

// Reads the chunks in order; every failure names the chunk.
class Reader {
 public:
  Reader(std::string_view bytes, const std::string& source) : bytes_(bytes), source_(source) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw Error(source_, where + ": " + what);
  }

  bool atEnd() const { return at_ == bytes_.size(); }

  void magic() {
    if (bytes_.substr(0, kMagic.size()) != kMagic) fail("start", "not a calibration log (no NAOCALLOG line)");
    at_ = kMagic.size();
  }

  // One chunk: its JSON (an object) and its payload.
  std::pair<nlohmann::json, std::string_view> chunk(const std::string& where) {
    const std::uint32_t jsonLength = u32(where, "the JSON's length");
    if (jsonLength > kMaxJson) fail(where, "JSON of " + std::to_string(jsonLength) + " bytes (at most " + std::to_string(kMaxJson) + ")");
    const std::string_view text = take(where, jsonLength, "JSON");
    nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
    if (j.is_discarded() || !j.is_object()) fail(where, "not a JSON object");
    const std::uint32_t payloadLength = u32(where, "the payload's length");
    if (payloadLength > kMaxPayload) fail(where, "payload of " + std::to_string(payloadLength) + " bytes (at most " + std::to_string(kMaxPayload) + ")");
    return {std::move(j), take(where, payloadLength, "payload")};
  }

 private:
  std::uint32_t u32(const std::string& where, const char* what) {
    const std::string_view b = take(where, 4, what);
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(static_cast<unsigned char>(b[i])) << (8 * i);
    return v;
  }
  std::string_view take(const std::string& where, std::size_t n, const char* what) {
    if (bytes_.size() - at_ < n)
      fail(where, std::string("truncated: the ") + what + " needs " + std::to_string(n) + " bytes, " +
                      std::to_string(bytes_.size() - at_) + " are left");
    const std::string_view s = bytes_.substr(at_, n);
    at_ += n;
    return s;
  }

  std::string_view bytes_;
  const std::string& source_;
  std::size_t at_ = 0;
};

// A member of a chunk's JSON, checked; failures name the chunk and the key.
template <class T>
T field(const Reader& r, const nlohmann::json& j, const std::string& where, const char* key) {
  const auto it = j.find(key);
  if (it == j.end()) r.fail(where, std::string("'") + key + "' missing");
  try {
    return it->get<T>();
  } catch (const nlohmann::json::exception&) {
    r.fail(where, std::string("'") + key + "' has the wrong type");
  }
}

double finiteNumber(const Reader& r, const nlohmann::json& j, const std::string& where, const char* key) {
  const auto it = j.find(key);
  if (it == j.end()) r.fail(where, std::string("'") + key + "' missing");
  if (!it->is_number() || !std::isfinite(it->get<double>())) r.fail(where, std::string("'") + key + "' is not a finite number");
  return it->get<double>();
}

template <std::size_t N>
std::array<double, N> finiteArray(const Reader& r, const nlohmann::json& j, const std::string& where, const char* key) {
  const auto it = j.find(key);
  if (it == j.end()) r.fail(where, std::string("'") + key + "' missing");
  if (!it->is_array() || it->size() != N) r.fail(where, std::string("'") + key + "' is not " + std::to_string(N) + " numbers");
  std::array<double, N> a{};
  for (std::size_t i = 0; i < N; ++i) {
    if (!(*it)[i].is_number() || !std::isfinite((*it)[i].get<double>()))
      r.fail(where, std::string("'") + key + "' element " + std::to_string(i) + " is not a finite number");
    a[i] = (*it)[i].get<double>();
  }
  return a;
}

}  // namespace

std::string serializeCalibrationLog(const CalibrationLog& log) {
  std::string out(kMagic);
  putChunk(out, {{"format", kFormat}, {"head_id", log.headId}, {"backend", log.backend}});
  for (const CalibrationLogRecord& r : log.records) {
    const CameraImage& im = r.image;
    putChunk(out,
             {{"view", r.viewId},
              {"camera", cameraName(im.camera)},
              {"time", im.timestamp},
              {"width", im.width},
              {"height", im.height},
              {"joints", r.joints},
              {"imu", {r.imuAngle.x(), r.imuAngle.y()}},
              {"accepted", r.accepted},
              {"reason", r.reason}},
             std::string_view(reinterpret_cast<const char*>(im.yuyv.data()), im.yuyv.size()));
  }
  putChunk(out, {{"end", true}, {"records", log.records.size()}});
  return out;
}

CalibrationLog parseCalibrationLog(std::string_view bytes, const std::string& source) {
  Reader r(bytes, source);
  r.magic();
  CalibrationLog log;
  {
    const auto [h, payload] = r.chunk("header");
    const int format = field<int>(r, h, "header", "format");
    if (format != kFormat) r.fail("header", "format " + std::to_string(format) + " (this program reads " + std::to_string(kFormat) + ")");
    log.headId = field<std::string>(r, h, "header", "head_id");
    log.backend = field<std::string>(r, h, "header", "backend");
    if (log.headId.empty()) r.fail("header", "'head_id' is empty");
  }
  for (std::size_t k = 1;; ++k) {
    const std::string where = "record " + std::to_string(k);
    if (r.atEnd()) r.fail(where, "truncated: the log ends after record " + std::to_string(k - 1) + " without its end marker");
    const auto [j, payload] = r.chunk(where);
    if (j.contains("end")) {
      const auto count = field<std::size_t>(r, j, "end marker", "records");
      if (count != log.records.size())
        r.fail("end marker", "says " + std::to_string(count) + " records, the log holds " + std::to_string(log.records.size()));
      if (!r.atEnd()) r.fail("end marker", "bytes after it");
      return log;
    }
    CalibrationLogRecord rec;
    rec.viewId = field<int>(r, j, where, "view");
    const std::string camera = field<std::string>(r, j, where, "camera");
    if (camera != "top" && camera != "bottom") r.fail(where, "'camera' is '" + camera + "', not top or bottom");
    rec.image.camera = camera == "top" ? CameraId::Top : CameraId::Bottom;
    rec.image.timestamp = finiteNumber(r, j, where, "time");
    rec.image.width = field<int>(r, j, where, "width");
    rec.image.height = field<int>(r, j, where, "height");
    if (rec.image.width < 2 || rec.image.width > 8192 || rec.image.width % 2 || rec.image.height < 1 || rec.image.height > 8192)
      r.fail(where, "image size " + std::to_string(rec.image.width) + "x" + std::to_string(rec.image.height) +
                        " (2..8192 x 1..8192, even width)");
    const std::size_t expected = static_cast<std::size_t>(rec.image.width) * rec.image.height * 2;
    if (payload.size() != expected)
      r.fail(where, "the image holds " + std::to_string(payload.size()) + " bytes, " + std::to_string(rec.image.width) + "x" +
                        std::to_string(rec.image.height) + " YUYV needs " + std::to_string(expected));
    rec.image.yuyv.assign(payload.begin(), payload.end());
    rec.joints = finiteArray<NumJoints>(r, j, where, "joints");
    const auto imu = finiteArray<2>(r, j, where, "imu");
    rec.imuAngle = Eigen::Vector2d(imu[0], imu[1]);
    rec.accepted = field<bool>(r, j, where, "accepted");
    rec.reason = field<std::string>(r, j, where, "reason");
    log.records.push_back(std::move(rec));
  }
}

CalibrationLog readCalibrationLog(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot be read");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) throw Error(path, "read error");
  return parseCalibrationLog(bytes.str(), path);
}

}  // namespace nao::calibration
