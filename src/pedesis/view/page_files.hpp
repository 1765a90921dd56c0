#pragma once
// The viewer page built from web/viewer (index.html, viewer.js, viewer.css, its icon),
// embedded in the binary when it is built, so that `pedesis view` and `--export` work
// wherever the binary is, without the build directory. A build without Node.js has no page: then
// page_file answers nothing and page_missing says how to get it.
#include <optional>
#include <string>
#include <string_view>

namespace pedesis::view {

struct PageFile {
    std::string_view bytes;
    const char* content_type;
};

// "index.html", "viewer.js", "viewer.css", "favicon.ico" (an SVG), or "viewer.js.sha256" and
// "viewer.css.sha256" (the CSP source expression 'sha256-…' of the script's and the style's
// bytes, computed when the page is built: the --export file allows them inline by these);
// none for another name or without a page.
std::optional<PageFile> page_file(std::string_view name);

// The Content-Security-Policy every served file of the page carries: scripts and styles only
// from the server itself (no inline script, <style> or style attribute), so that a string
// from a run that reached the document as markup could not run.
std::string_view page_security_policy();

// The message for a build without the page: what it needs and how to get it.
std::string page_missing();

} // namespace pedesis::view
