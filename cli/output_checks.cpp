#include "output_checks.h"

#include <system_error>

#include "meadow/core/error.h"
#include "meadow/core/temporaries.h"

namespace meadow::cli {

namespace fs = std::filesystem;

bool sameFile(const fs::path& a, const fs::path& b) {
    std::error_code ec;
    return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

void refuseToReplace(const fs::path& path, const std::string& option,
                     const std::function<bool(const fs::path&)>& isOurs, const std::string& why) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (ec == std::errc::too_many_symbolic_link_levels)
        throw Error(path.string() + " (" + option +
                    ") is a loop of symbolic links; choose another path");
    if (!fs::exists(status)) return;
    if (fs::is_directory(status))
        throw Error("cannot write " + path.string() + " (" + option +
                    "): it is a folder; give a file name");
    if (!isOurs(path))
        throw Error("refusing to overwrite " + path.string() + " (" + option + "): " + why +
                    "; choose another path or remove it first");
}

void refuseFolderOfOthers(const fs::path& folder, const std::string& option,
                          const std::function<bool(const std::string&)>& isOurs,
                          const std::string& why) {
    std::error_code ec;
    const fs::file_status status = fs::status(folder, ec);
    if (!fs::exists(status)) return;
    if (!fs::is_directory(status))
        throw Error("cannot write into " + folder.string() + " (" + option +
                    "): it is a file; give a folder");
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        std::string name = it->path().filename().string();
        if (const auto tmp = name.find(".tmp."); tmp != std::string::npos) name.resize(tmp);
        if (!isOurs(name))
            throw Error("refusing to write into " + folder.string() + " (" + option + "): " + why +
                        " (" + it->path().filename().string() +
                        "); choose another folder or remove it first");
    }
}

bool isOverlayName(const std::string& name) {
    constexpr std::string_view kPrefix = "frame_", kSuffix = ".png";
    return name.size() > kPrefix.size() + kSuffix.size() && name.starts_with(kPrefix) &&
           name.ends_with(kSuffix) &&
           name.find_first_not_of("0123456789", kPrefix.size()) == name.size() - kSuffix.size();
}

}  // namespace meadow::cli
