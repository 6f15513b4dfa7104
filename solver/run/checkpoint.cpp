#include "solver/run/checkpoint.hpp"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <sstream>

#include <fmt/format.h>

#include "io/h5/h5_reader.hpp"
#include "io/h5/h5_series.hpp"

namespace raceway::run {

namespace {

// Version 2: the payload's CRC-32 (payload_crc32).
constexpr long long kCheckpointVersion = 2;
constexpr CheckpointKind kKinds[] = {CheckpointKind::periodic, CheckpointKind::wall_clock, CheckpointKind::signal};

/// The first line where two texts differ, for a message.
std::string first_difference(const std::string& a, const std::string& b) {
  std::istringstream sa(a), sb(b);
  std::string la, lb;
  for (int line = 1;; ++line) {
    const bool more_a = static_cast<bool>(std::getline(sa, la)), more_b = static_cast<bool>(std::getline(sb, lb));
    if (!more_a && !more_b) return "they differ in line endings";
    if (!more_a || !more_b || la != lb)
      return fmt::format("line {}: the checkpoint's '{}', now '{}'", line, more_a ? la : "(end of file)",
                         more_b ? lb : "(end of file)");
  }
}

/// CRC-32 (zlib's crc32, the checksum gzip uses) over a checkpoint's payload: every field the
/// resume uses, each with its length, in one fixed order. A flipped bit anywhere in the stored
/// values (HDF5 keeps raw data and attributes without a checksum of its own) changes it.
class PayloadCrc {
 public:
  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const Bytef*>(data);
    while (n > 0) {  // crc32 takes a uInt length
      const auto part = static_cast<uInt>(std::min<std::size_t>(n, std::size_t{1} << 30));
      crc_ = crc32(crc_, p, part);
      p += part, n -= part;
    }
  }
  void number(std::uint64_t v) { bytes(&v, sizeof v); }
  void number(double v) { bytes(&v, sizeof v); }
  void text(const std::string& s) { number(static_cast<std::uint64_t>(s.size())), bytes(s.data(), s.size()); }
  void values(const std::vector<double>& v) {
    number(static_cast<std::uint64_t>(v.size()));
    bytes(v.data(), v.size() * sizeof(double));
  }
  unsigned long value() const { return crc_; }

 private:
  uLong crc_ = crc32(0L, Z_NULL, 0);
};

unsigned long payload_crc(const Checkpoint& cp) {
  PayloadCrc crc;
  crc.text(checkpoint_kind_name(cp.kind));
  crc.number(static_cast<std::uint64_t>(cp.sample));
  crc.number(cp.time);
  crc.text(cp.fingerprint.scene_text);
  crc.text(cp.fingerprint.build);
  crc.text(cp.fingerprint.options);
  crc.values(cp.state);
  crc.values(cp.restart_times);
  crc.number(static_cast<std::uint64_t>(cp.values.size()));
  for (const auto& [name, value] : cp.values) crc.text(name), crc.number(value);
  crc.number(static_cast<std::uint64_t>(cp.unwritten_rows.size()));
  for (const auto& [series, rows] : cp.unwritten_rows) crc.text(series), crc.values(rows);
  crc.number(static_cast<std::uint64_t>(cp.partial_crc.size()));
  for (const auto& [series, value] : cp.partial_crc) crc.text(series), crc.number(value);
  return crc.value();
}

}  // namespace

const char* checkpoint_kind_name(CheckpointKind kind) {
  switch (kind) {
    case CheckpointKind::periodic: return "periodic";
    case CheckpointKind::wall_clock: return "wall_clock";
    case CheckpointKind::signal: return "signal";
  }
  return "?";
}

std::string checkpoint_path(const std::string& output_path) { return output_path + ".checkpoint"; }

void write_checkpoint(const std::string& path, const Checkpoint& cp) {
  // Sealed: a resume checks every byte of it before HDF5 reads any (h5::sealed_file_problem).
  auto file = h5::H5SeriesWriter::create(path, {.gzip_level = 0, .shuffle = false, .sealed = true});
  file.set_attribute("/", "checkpoint_version", kCheckpointVersion);
  file.set_attribute("/", "kind", std::string(checkpoint_kind_name(cp.kind)));
  file.set_attribute("/", "sample", static_cast<long long>(cp.sample));
  file.set_attribute("/", "time", cp.time);
  file.set_attribute("/", "scene_text", cp.fingerprint.scene_text);
  file.set_attribute("/", "build", cp.fingerprint.build);
  file.set_attribute("/", "options", cp.fingerprint.options);
  file.write_array("/state", {cp.state.size()}, cp.state, "-", "the state vector at the checkpoint's time");
  file.write_array("/restart_times", {cp.restart_times.size()}, cp.restart_times, "s",
                   "times at which CVODE restarted off the periodic checkpoints");
  for (const auto& [name, value] : cp.values) file.set_attribute("/values", name, value);
  for (const auto& [series, value] : cp.partial_crc) file.set_attribute("/partial_crc32", series, value);
  // The unwritten rows of all series in one dataset (one object, not one per series: a checkpoint is
  // written in about 1 ms rather than 20), their series and lengths beside it.
  std::string names;
  std::vector<double> lengths, rows;
  for (const auto& [series, values] : cp.unwritten_rows) {
    names += series + "\n";
    lengths.push_back(static_cast<double>(values.size()));
    rows.insert(rows.end(), values.begin(), values.end());
  }
  file.set_attribute("/", "unwritten_series", names);
  file.write_array("/unwritten_lengths", {lengths.size()}, lengths, "-", "values of each series in /unwritten_rows");
  file.write_array("/unwritten_rows", {rows.size()}, rows, "-", "rows of the series not yet in the output file");
  file.set_attribute("/", "payload_crc32", static_cast<long long>(payload_crc(cp)));
  file.commit();
}

std::optional<Checkpoint> read_checkpoint(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  try {
    if (const std::string problem = h5::sealed_file_problem(path); !problem.empty()) throw std::runtime_error(problem);
    const h5::H5Reader r(path);
    if (const double version = r.number_attribute("/", "checkpoint_version");
        version != static_cast<double>(kCheckpointVersion))
      throw std::runtime_error(fmt::format("checkpoint version {}, this build reads version {}", version, kCheckpointVersion));
    Checkpoint cp;
    const std::string kind = r.string_attribute("/", "kind");
    bool known_kind = false;
    for (const CheckpointKind k : kKinds)
      if (kind == checkpoint_kind_name(k)) cp.kind = k, known_kind = true;
    if (!known_kind) throw std::runtime_error(fmt::format("unknown checkpoint kind '{}'", kind));
    cp.sample = static_cast<long>(r.number_attribute("/", "sample"));
    cp.time = r.number_attribute("/", "time");
    cp.fingerprint = {r.string_attribute("/", "scene_text"), r.string_attribute("/", "build"),
                      r.string_attribute("/", "options")};
    cp.state = r.doubles("/state");
    cp.restart_times = r.doubles("/restart_times");
    for (const std::string& name : r.attribute_names("/values")) cp.values[name] = r.number_attribute("/values", name);
    if (r.has("/partial_crc32"))
      for (const std::string& series : r.attribute_names("/partial_crc32"))
        cp.partial_crc[series] = r.number_attribute("/partial_crc32", series);
    const std::vector<double> lengths = r.doubles("/unwritten_lengths"), rows = r.doubles("/unwritten_rows");
    std::istringstream names(r.string_attribute("/", "unwritten_series"));
    std::size_t offset = 0;
    for (const double length : lengths) {
      std::string series;
      const auto n = static_cast<std::size_t>(length);
      if (!std::getline(names, series) || offset + n > rows.size()) throw std::runtime_error("inconsistent unwritten rows");
      cp.unwritten_rows[series].assign(rows.begin() + static_cast<std::ptrdiff_t>(offset),
                                       rows.begin() + static_cast<std::ptrdiff_t>(offset + n));
      offset += n;
    }
    if (offset != rows.size()) throw std::runtime_error("inconsistent unwritten rows");
    const double stored_crc = r.number_attribute("/", "payload_crc32");
    if (stored_crc != static_cast<double>(payload_crc(cp)))
      throw std::runtime_error(fmt::format("its payload's CRC-32 is {}, its stored checksum (payload_crc32) {}: the "
                                           "file is damaged", payload_crc(cp), stored_crc));
    return cp;
  } catch (const std::runtime_error& e) {
    throw ResumeRefused(fmt::format("cannot resume: the checkpoint '{}' is unreadable ({}); run without --resume to "
                                    "start again", path, e.what()));
  }
}

void require_same_run(const RunFingerprint& checkpoint, const RunFingerprint& now, const std::string& path) {
  std::string reason;
  if (checkpoint.scene_text != now.scene_text)
    reason = "the scene differs from the checkpoint's: " + first_difference(checkpoint.scene_text, now.scene_text);
  else if (checkpoint.build != now.build)
    reason = fmt::format("the checkpoint was written by another build of raceway ({}), this is {}", checkpoint.build,
                         now.build);
  else if (checkpoint.options != now.options)
    reason = fmt::format("the checkpoint was written with other options ('{}'), now '{}'", checkpoint.options,
                         now.options);
  if (!reason.empty())
    throw ResumeRefused(fmt::format("cannot resume from '{}': {}; run without --resume to start again", path, reason));
}

}  // namespace raceway::run

namespace raceway::run {

void require_fits(const Checkpoint& cp, std::size_t state_size, long samples, double dt, const std::string& path) {
  std::string reason;
  const auto finite = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  };
  const double sample_time = static_cast<double>(cp.sample) * dt;
  if (cp.state.size() != state_size)
    reason = fmt::format("its state has {} values, the scene's model {}", cp.state.size(), state_size);
  else if (!finite(cp.state))
    reason = "its state holds a value that is not finite";
  else if (cp.sample < 0 || cp.sample >= samples)
    reason = fmt::format("its output sample {} is outside the run's 0..{}", cp.sample, samples - 1);
  else if (!std::isfinite(cp.time) || std::fabs(cp.time - sample_time) > 1e-9 * std::max(dt, std::fabs(sample_time)))
    reason = fmt::format("its time {:.17g} s is not that of its output sample {} ({:.17g} s)", cp.time, cp.sample,
                         sample_time);
  else if (!finite(cp.restart_times) || std::any_of(cp.restart_times.begin(), cp.restart_times.end(),
                                                    [&](double t) { return t < 0 || t > cp.time; }))
    reason = fmt::format("a restart time is not within 0..{:.9g} s", cp.time);
  if (!reason.empty())
    throw ResumeRefused(fmt::format("cannot resume from '{}': {}; run without --resume to start again", path, reason));
}

}  // namespace raceway::run
