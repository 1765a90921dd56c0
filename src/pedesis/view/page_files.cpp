#include "pedesis/view/page_files.hpp"

#include <cstddef>

// The assembler's .incbin copies each built file into the binary's read-only data at
// build time (web/viewer/CMakeLists.txt defines PEDESIS_EMBEDDED_PAGE, the directory,
// and rebuilds this file when the page changes): no multi-megabyte array literal for the
// compiler, and no path to the build directory at run time.
#ifdef PEDESIS_EMBEDDED_PAGE
#define PEDESIS_EMBED(symbol, file)                                                                \
    asm(".section .rodata\n"                                                                       \
        ".balign 16\n"                                                                             \
        ".global " #symbol "_begin\n" #symbol "_begin:\n"                                          \
        ".incbin \"" PEDESIS_EMBEDDED_PAGE "/" file "\"\n"                                         \
        ".global " #symbol "_end\n" #symbol "_end:\n"                                              \
        ".previous\n");                                                                            \
    extern "C" const char symbol##_begin[];                                                        \
    extern "C" const char symbol##_end[];

PEDESIS_EMBED(pedesis_page_index_html, "index.html")
PEDESIS_EMBED(pedesis_page_viewer_js, "viewer.js")
PEDESIS_EMBED(pedesis_page_viewer_css, "viewer.css")
PEDESIS_EMBED(pedesis_page_favicon_svg, "favicon.svg")
PEDESIS_EMBED(pedesis_page_viewer_js_sha256, "viewer.js.sha256")
PEDESIS_EMBED(pedesis_page_viewer_css_sha256, "viewer.css.sha256")
#endif

namespace pedesis::view {

std::optional<PageFile> page_file(std::string_view name) {
#ifdef PEDESIS_EMBEDDED_PAGE
    const auto span = [](const char* begin, const char* end) {
        return std::string_view(begin, static_cast<std::size_t>(end - begin));
    };
    if (name == "index.html")
        return PageFile{span(pedesis_page_index_html_begin, pedesis_page_index_html_end),
                        "text/html; charset=utf-8"};
    if (name == "viewer.js")
        return PageFile{span(pedesis_page_viewer_js_begin, pedesis_page_viewer_js_end),
                        "text/javascript; charset=utf-8"};
    if (name == "viewer.css")
        return PageFile{span(pedesis_page_viewer_css_begin, pedesis_page_viewer_css_end),
                        "text/css; charset=utf-8"};
    // the icon is an SVG under the name browsers ask for by themselves
    if (name == "favicon.ico")
        return PageFile{span(pedesis_page_favicon_svg_begin, pedesis_page_favicon_svg_end),
                        "image/svg+xml"};
    if (name == "viewer.js.sha256")
        return PageFile{
            span(pedesis_page_viewer_js_sha256_begin, pedesis_page_viewer_js_sha256_end),
            "text/plain; charset=utf-8"};
    if (name == "viewer.css.sha256")
        return PageFile{
            span(pedesis_page_viewer_css_sha256_begin, pedesis_page_viewer_css_sha256_end),
            "text/plain; charset=utf-8"};
#else
    (void)name;
#endif
    return std::nullopt;
}

std::string_view page_security_policy() {
    return "default-src 'none'; script-src 'self'; style-src 'self'; img-src 'self' data: blob:; "
           "connect-src 'self'; worker-src 'self' blob:; base-uri 'none'; form-action 'none'; "
           "frame-ancestors 'none'";
}

std::string page_missing() {
    return "pedesis view: this build has no viewer page: building it needs Node.js and npm; "
           "install them (make deps) and build again (make build)";
}

} // namespace pedesis::view
