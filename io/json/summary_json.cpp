// raceway run summaries: tiny ordered JSON writer (see summary_json.hpp for why it is hand-written).
#include "io/json/summary_json.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <cctype>
#include <variant>

#include <fmt/format.h>
#include <unistd.h>

namespace raceway::json {

namespace {
struct RawJson {
  std::string text;
};
}  // namespace

struct JsonObject::Entry {
  std::string key;
  std::variant<double, long long, bool, std::string, std::vector<double>, JsonObject, RawJson> value;
};

JsonObject::JsonObject() = default;
JsonObject::~JsonObject() = default;
JsonObject::JsonObject(const JsonObject&) = default;
JsonObject::JsonObject(JsonObject&&) noexcept = default;
JsonObject& JsonObject::operator=(const JsonObject&) = default;
JsonObject& JsonObject::operator=(JsonObject&&) noexcept = default;
bool JsonObject::empty() const noexcept { return entries_.empty(); }
std::size_t JsonObject::size() const noexcept { return entries_.size(); }

JsonObject& JsonObject::put(const std::string& key, Entry&& entry) {
  auto it = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.key == key; });
  if (it != entries_.end()) {
    it->value = std::move(entry.value);
  } else {
    entries_.push_back(std::move(entry));
  }
  return *this;
}

JsonObject& JsonObject::add(const std::string& key, double v) { return put(key, Entry{key, v}); }
JsonObject& JsonObject::add(const std::string& key, long long v) { return put(key, Entry{key, v}); }
JsonObject& JsonObject::add(const std::string& key, bool v) { return put(key, Entry{key, v}); }
JsonObject& JsonObject::add(const std::string& key, std::string v) { return put(key, Entry{key, std::move(v)}); }
JsonObject& JsonObject::add(const std::string& key, const char* v) { return add(key, std::string(v)); }
JsonObject& JsonObject::add(const std::string& key, std::vector<double> v) { return put(key, Entry{key, std::move(v)}); }
JsonObject& JsonObject::add(const std::string& key, JsonObject v) { return put(key, Entry{key, std::move(v)}); }
JsonObject& JsonObject::add_raw(const std::string& key, std::string text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  return put(key, Entry{key, RawJson{std::move(text)}});
}

namespace {

void append_string(std::string& out, const std::string& s) {
  out += '"';
  for (const char ch : s) {
    switch (ch) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(ch) < 0x20) {
          out += fmt::format("\\u{:04x}", static_cast<unsigned>(static_cast<unsigned char>(ch)));
        } else {
          out += ch;  // UTF-8 bytes pass through
        }
    }
  }
  out += '"';
}

void append_double(std::string& out, double v) {
  if (!std::isfinite(v)) {
    out += "null";
    return;
  }
  // fmt's "{}" is the shortest string that reads back to the same double (at most 17 digits).
  const std::string s = fmt::format("{}", v);
  out += s;
  if (s.find_first_of(".eE") == std::string::npos) out += ".0";  // keep 3.0 a float for readers
}

}  // namespace

void JsonObject::dump_to(std::string& out, int indent, int depth) const {
  if (entries_.empty()) {
    out += "{}";
    return;
  }
  const bool pretty = indent > 0;
  const std::string pad = pretty ? std::string(static_cast<std::size_t>(indent * (depth + 1)), ' ') : "";
  out += pretty ? "{\n" : "{";
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    const Entry& e = entries_[i];
    out += pad;
    append_string(out, e.key);
    out += pretty ? ": " : ":";
    std::visit(
        [&](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, double>) {
            append_double(out, v);
          } else if constexpr (std::is_same_v<T, long long>) {
            out += std::to_string(v);
          } else if constexpr (std::is_same_v<T, bool>) {
            out += v ? "true" : "false";
          } else if constexpr (std::is_same_v<T, std::string>) {
            append_string(out, v);
          } else if constexpr (std::is_same_v<T, std::vector<double>>) {
            out += '[';
            for (std::size_t k = 0; k < v.size(); ++k) {
              if (k > 0) out += pretty ? ", " : ",";
              append_double(out, v[k]);
            }
            out += ']';
          } else if constexpr (std::is_same_v<T, RawJson>) {
            for (const char c : v.text) {
              if (c == '\n' && !pretty) continue;
              out += c;
              if (c == '\n') out += pad;
            }
          } else {
            v.dump_to(out, indent, depth + 1);
          }
        },
        e.value);
    if (i + 1 < entries_.size()) out += ',';
    if (pretty) out += '\n';
  }
  if (pretty) out += std::string(static_cast<std::size_t>(indent * depth), ' ');
  out += '}';
}

std::string JsonObject::dump(int indent) const {
  std::string out;
  dump_to(out, indent, 0);
  return out;
}

void write_json_file(const std::string& path, const JsonObject& obj) {
  const std::string tmp = path + ".tmp";
  const std::string text = obj.dump() + "\n";
  auto fail = [&](const std::string& what) {
    throw std::runtime_error(fmt::format("write_json_file: {} '{}' failed: {}", what, tmp, std::strerror(errno)));
  };
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr) fail("opening");
  const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size() && std::fflush(f) == 0;
  const int saved_errno = errno;
  if (written) (void)::fsync(::fileno(f));  // durable before the rename
  if (std::fclose(f) != 0 || !written) {
    if (!written) errno = saved_errno;
    fail("writing");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::runtime_error(fmt::format("write_json_file: renaming '{}' to '{}' failed: {}", tmp, path, ec.message()));
}

}  // namespace raceway::json
