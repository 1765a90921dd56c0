#pragma once
// The viewer page built from web/viewer (index.html, viewer.js, viewer.css), embedded in
// the binary when it is built, so that `pedesis view` and `--export` work wherever the
// binary is, without the build directory. A build without Node.js has no page: then
// page_file answers nothing and page_missing says how to get it.
#include <optional>
#include <string>
#include <string_view>

namespace pedesis::view {

struct PageFile {
    std::string_view bytes;
    const char* content_type;
};

// "index.html", "viewer.js" or "viewer.css"; none for another name or without a page.
std::optional<PageFile> page_file(std::string_view name);

// The message for a build without the page: what it needs and how to get it.
std::string page_missing();

} // namespace pedesis::view
