#include "core/whole_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

#include "core/error.h"

namespace ranryu {
namespace {

// fsync(2) of a file or a folder; a failure costs durability, not the write, so it is not reported.
void sync_path(const std::filesystem::path& p) {
    const int fd = ::open(p.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return;
    ::fsync(fd);
    ::close(fd);
}

}  // namespace

void write_whole_file(const std::filesystem::path& path, std::span<const std::string_view> parts, const std::string& where,
                      bool sync) {
    std::filesystem::path tmp = path;
    tmp += ".tmp";
    std::error_code ignored;
    {
        std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
        if (!f) throw Error(where + std::strerror(errno));
        for (std::string_view part : parts) f.write(part.data(), std::streamsize(part.size()));
        f.close();
        if (!f) {
            const std::string why = std::strerror(errno);
            std::filesystem::remove(tmp, ignored);
            throw Error(where + why);
        }
    }
    if (sync) sync_path(tmp);
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ignored);
        throw Error(where + ec.message());
    }
    if (sync) sync_path(path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path());
}

}  // namespace ranryu
