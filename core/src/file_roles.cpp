#include "flagsim/core/file_roles.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <filesystem>
#include <system_error>

#include "flagsim/core/errors.hpp"

namespace flagsim {
namespace fs = std::filesystem;

void FileRoles::input(std::string path, std::string what) {
  if (!path.empty()) inputs_.push_back({std::move(path), std::move(what)});
}

void FileRoles::output(std::string path, std::string what) {
  if (!path.empty()) outputs_.push_back({std::move(path), std::move(what)});
}

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {
  }, sb{};
  if (::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0)
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  // One of them does not exist (yet): the same path once resolved.
  std::error_code ea, eb;
  const fs::path pa = fs::weakly_canonical(fs::absolute(a, ea), ea);
  const fs::path pb = fs::weakly_canonical(fs::absolute(b, eb), eb);
  return !ea && !eb && pa == pb;
}

void FileRoles::check() const {
  for (std::size_t o = 0; o < outputs_.size(); ++o) {
    const Role& out = outputs_[o];
    for (const Role& in : inputs_)
      if (same_file(out.path, in.path))
        throw UserError(fmt::format("{}: {} would overwrite {} ({}); choose another output path",
                                    out.path, out.what, in.what, in.path));
    for (std::size_t other = 0; other < o; ++other)
      if (same_file(out.path, outputs_[other].path))
        throw UserError(
            fmt::format("{}: {} and {} ({}) would be the same file; choose another "
                        "output path",
                        out.path, out.what, outputs_[other].what, outputs_[other].path));
  }
}

CreatedDirectories::CreatedDirectories(CreatedDirectories&& other) noexcept
    : created_(std::move(other.created_)) {
  other.created_.clear();
}

CreatedDirectories& CreatedDirectories::operator=(CreatedDirectories&& other) noexcept {
  if (this != &other) {
    remove_empty();
    created_ = std::move(other.created_);
    other.created_.clear();
  }
  return *this;
}

CreatedDirectories::~CreatedDirectories() {
  remove_empty();
}

bool CreatedDirectories::create(const std::string& dir, std::error_code& error) {
  error.clear();
  if (dir.empty()) return true;
  // The missing ancestors, outermost first, each created (and recorded) in turn.
  std::vector<fs::path> missing;
  for (fs::path p = fs::path(dir).lexically_normal(); !p.empty() && !fs::exists(p, error);
       p = p.parent_path()) {
    missing.push_back(p);
    if (p == p.parent_path()) break;
  }
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    if (it->filename().empty()) continue;  // "a/b/" normalises with a trailing empty name
    if (!fs::create_directory(*it, error) && error) return false;
    created_.push_back(it->string());
  }
  return fs::is_directory(dir, error);
}

void CreatedDirectories::remove_empty() noexcept {
  for (auto it = created_.rbegin(); it != created_.rend(); ++it) {
    std::error_code ignored;
    if (fs::is_empty(*it, ignored)) fs::remove(*it, ignored);
  }
  created_.clear();
}

void check_file_name_part(const std::string& name, const std::string& what) {
  bool control = false;
  for (unsigned char c : name) control = control || c < 0x20 || c == 0x7f;
  if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos ||
      control || name.size() > 200)
    throw UserError(fmt::format(
        "{} cannot name an output file (it must be one file name: no '/', no control "
        "characters, not '.' or '..', at most 200 bytes); give -o OUT.h5 or output.file",
        what));
}

}  // namespace flagsim
