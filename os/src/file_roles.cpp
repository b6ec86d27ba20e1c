#include "flagsim/os/file_roles.hpp"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <climits>
#include <filesystem>
#include <system_error>
#include <unordered_map>
#include <unordered_set>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/message.hpp"

namespace flagsim {
namespace fs = std::filesystem;

void FileRoles::input(std::string path, std::string what) {
  if (!path.empty()) inputs_.push_back({std::move(path), std::move(what)});
}

void FileRoles::output(std::string path, std::string what) {
  if (!path.empty()) outputs_.push_back({std::move(path), std::move(what)});
}

void FileRoles::outputs_in(const std::string& dir, const std::vector<std::string>& names,
                           const std::string& what) {
  const fs::path base(dir);
  for (const std::string& name : names) outputs_.push_back({(base / name).string(), what});
}

namespace {

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// What identifies the file a path names: its device and inode where it
// exists, else the path made absolute with every existing directory (and
// symlink) on it resolved. Two paths with one key are one file.
std::string file_key(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) return fmt::format("i{}:{}", st.st_dev, st.st_ino);
  std::string key = "p";
  std::error_code ec;
  const fs::path p = fs::absolute(path, ec);
  if (ec) return key.append(path);
  const fs::path resolved = fs::weakly_canonical(p, ec);
  return key.append((ec ? p.lexically_normal() : resolved).native());
}

// The output's directory (its nearest existing ancestor, when it is still to
// be made) must be a directory this process can write into.
void check_writable_directory(const std::string& path, const std::string& what,
                              std::unordered_set<std::string>& seen) {
  fs::path dir = fs::path(path).parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  while (!fs::exists(dir, ec) && dir.has_parent_path() && dir != dir.parent_path())
    dir = dir.parent_path();
  if (!seen.insert(dir.string()).second) return;
  if (!fs::exists(dir, ec)) return;
  if (!fs::is_directory(dir, ec))
    throw UserError(fmt::format("{} {}: {} is a file, not a directory", what, printable(path),
                                printable(dir.string())));
  if (::access(dir.c_str(), W_OK) != 0)
    throw UserError(fmt::format("{} {}: cannot write into {} (check its permissions)", what,
                                printable(path), printable(dir.string())));
}

}  // namespace

void check_regular_file(const std::string& path, const std::string& what) {
  bool too_long = path.size() >= PATH_MAX;
  for (const fs::path& part : fs::path(path))
    too_long = too_long || part.native().size() > NAME_MAX;
  if (too_long)
    throw UserError(fmt::format(
        "{} {}: too long a path ({} bytes; this system takes {} in all, {} in one name)", what,
        printable(path), path.size(), PATH_MAX - 1, NAME_MAX));
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    throw UserError(fmt::format("{} {}: is {}, expected a regular file", what, printable(path),
                                kind_of(st.st_mode)));
}

bool same_file(const std::string& a, const std::string& b) {
  return file_key(a) == file_key(b);
}

void FileRoles::check() const {
  std::unordered_map<std::string, const Role*> inputs, outputs;
  for (const Role& in : inputs_) {
    check_regular_file(in.path, in.what);
    inputs.emplace(file_key(in.path), &in);
  }
  std::unordered_set<std::string> directories;
  for (const Role& out : outputs_) {
    check_regular_file(out.path, out.what);
    const std::string key = file_key(out.path);
    if (const auto in = inputs.find(key); in != inputs.end())
      throw UserError(fmt::format("{}: {} would overwrite {} ({}); choose another output path",
                                  printable(out.path), out.what, in->second->what,
                                  printable(in->second->path)));
    if (const auto [other, added] = outputs.emplace(key, &out); !added)
      throw UserError(fmt::format(
          "{}: {} and {} ({}) would be the same file; choose another output path",
          printable(out.path), out.what, other->second->what, printable(other->second->path)));
    check_writable_directory(out.path, out.what, directories);
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
