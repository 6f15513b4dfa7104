#include "solver/run/checkpoint.hpp"

#include <filesystem>
#include <sstream>

#include <fmt/format.h>

#include "io/h5/h5_reader.hpp"
#include "io/h5/h5_series.hpp"

namespace raceway::solver {

namespace {

constexpr long long kCheckpointVersion = 1;
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
  auto file = io::H5SeriesWriter::create(path, {.gzip_level = 0, .shuffle = false});
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
  file.commit();
}

std::optional<Checkpoint> read_checkpoint(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  try {
    const io::H5Reader r(path);
    if (r.number_attribute("/", "checkpoint_version") != static_cast<double>(kCheckpointVersion))
      throw std::runtime_error("another checkpoint version");
    Checkpoint cp;
    const std::string kind = r.string_attribute("/", "kind");
    for (const CheckpointKind k : kKinds)
      if (kind == checkpoint_kind_name(k)) cp.kind = k;
    cp.sample = static_cast<long>(r.number_attribute("/", "sample"));
    cp.time = r.number_attribute("/", "time");
    cp.fingerprint = {r.string_attribute("/", "scene_text"), r.string_attribute("/", "build"),
                      r.string_attribute("/", "options")};
    cp.state = r.doubles("/state");
    cp.restart_times = r.doubles("/restart_times");
    for (const std::string& name : r.attribute_names("/values")) cp.values[name] = r.number_attribute("/values", name);
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

}  // namespace raceway::solver
