#include "solver/driver/data_files.hpp"

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace raceway::driver {

namespace fs = std::filesystem;

std::vector<std::string> data_file_candidates(const std::string& name) {
  std::vector<std::string> out;
  if (const char* dir = std::getenv("RACEWAY_DATA_DIR"); dir && *dir) out.push_back((fs::path(dir) / name).string());
  std::error_code ec;
  const fs::path exe_dir = fs::read_symlink("/proc/self/exe", ec).parent_path();
  if (ec || exe_dir.empty()) return out;
  for (const fs::path& dir : {exe_dir.parent_path() / "share" / "raceway" / "data", exe_dir / "share" / "raceway" / "data"})
    out.push_back((dir / name).string());
  return out;
}

std::string data_file_path(const std::string& name) {
  const auto candidates = data_file_candidates(name);
  std::error_code ec;
  for (const auto& c : candidates)
    if (fs::is_regular_file(c, ec)) return fs::path(c).lexically_normal().string();
  return candidates.empty() ? name : candidates.front();
}

}  // namespace raceway::driver
