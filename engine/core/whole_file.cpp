#include "core/whole_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

#include "core/error.h"

namespace ranryu {

void write_whole_file(const std::filesystem::path& path, std::initializer_list<std::string_view> parts,
                      const std::string& where) {
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
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ignored);
        throw Error(where + ec.message());
    }
}

}  // namespace ranryu
