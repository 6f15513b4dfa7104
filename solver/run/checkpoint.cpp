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
  for (const auto& [series, rows] : cp.unwritten_rows)
    file.write_array("/unwritten" + series, {rows.size()}, rows, "-", "rows of the series not yet in the output file");
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
    constexpr std::string_view prefix = "/unwritten";
    if (r.has("/unwritten"))
      for (const std::string& d : r.dataset_paths("/unwritten")) cp.unwritten_rows[d.substr(prefix.size())] = r.doubles(d);
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
