#include "flagsim/data/disk_room.hpp"

#include <fmt/format.h>
#include <sys/resource.h>
#include <sys/statvfs.h>

#include <algorithm>
#include <filesystem>
#include <system_error>

namespace flagsim::data {
namespace fs = std::filesystem;

std::optional<std::string> no_room_for(const std::string& path, std::uintmax_t need_bytes) {
  std::uintmax_t room = UINTMAX_MAX;
  struct statvfs disk {};
  const fs::path dir = fs::path(path).has_parent_path() ? fs::path(path).parent_path() : ".";
  if (statvfs(dir.c_str(), &disk) == 0) room = std::uintmax_t(disk.f_bavail) * disk.f_frsize;
  // The file-size limit counts what the file holds already.
  struct rlimit limit {};
  std::error_code ec;
  const std::uintmax_t size = fs::exists(path, ec) ? fs::file_size(path, ec) : 0;
  if (getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY && !ec)
    room = std::min(room, std::uintmax_t(limit.rlim_cur) > size ? limit.rlim_cur - size : 0);
  if (room >= need_bytes) return std::nullopt;
  return fmt::format(
      "no room for more frames: {:.1f} MB left on the disk or under the file size "
      "limit, the next ones need {:.1f} MB",
      double(room) / 1e6, double(need_bytes) / 1e6);
}

}  // namespace flagsim::data
