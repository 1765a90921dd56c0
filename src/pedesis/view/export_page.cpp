#include "pedesis/view/export_page.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"
#include "pedesis/render/run_directory.hpp"
#include "pedesis/view/frame_arrays.hpp"
#include "pedesis/view/page_files.hpp"
#include "pedesis/view/run_data.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <openssl/evp.h>

#include <cctype>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>

namespace pedesis::view {

namespace {

// Typed arrays travel as base64 text (4 characters per 3 bytes), OpenSSL's encoder.
std::string base64(const std::string& bytes) {
    std::string out(4 * ((bytes.size() + 2) / 3) + 1, '\0');
    const int n = EVP_EncodeBlock(reinterpret_cast<unsigned char*>(out.data()),
                                  reinterpret_cast<const unsigned char*>(bytes.data()),
                                  static_cast<int>(bytes.size()));
    out.resize(static_cast<std::size_t>(n));
    return out;
}

std::string page_text(std::string_view name) {
    const std::optional<PageFile> file = page_file(name);
    if (!file) throw InputError(page_missing());
    return std::string(file->bytes);
}

void replace_once(std::string& text, const std::string& what, const std::string& with) {
    const auto at = text.find(what);
    if (at == std::string::npos)
        throw std::logic_error("export: the page's index.html lacks '" + what + "'");
    text.replace(at, what.size(), with);
}

// JSON text that may stand inside <script type="application/json">: no '<' (so no "</script"
// or "<!--" can end or change the element), and no '>' or '&' either, each written as its
// \u escape. These characters occur only inside JSON strings, where the escape means the
// same character to JSON.parse.
std::string json_for_html(const nlohmann::json& data) {
    // names come from files: bytes that are not UTF-8 become U+FFFD rather than an error
    const std::string text = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        if (c == '<')
            out += "\\u003c";
        else if (c == '>')
            out += "\\u003e";
        else if (c == '&')
            out += "\\u0026";
        else
            out += c;
    }
    return out;
}

// What stands between <script> and </script> (or <style> and </style>) as it is: nothing
// that ends the element or starts the parser's escaped states.
void check_inline(const std::string& text, std::string_view what, std::string_view end) {
    std::string lower(text);
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (lower.find(end) != std::string::npos || lower.find("<!--") != std::string::npos)
        throw std::logic_error(
            fmt::format("export: the page's {} holds '{}' or '<!--'", what, end));
}

// A path of this machine reduced to its last name (a directory's own for "runs/demo/").
std::string base_name(const std::filesystem::path& path) {
    std::filesystem::path p = path.lexically_normal();
    if (p.filename().empty()) p = p.parent_path();
    return p.filename().string();
}

} // namespace

void export_page(const ExportOptions& o) {
    std::string html = page_text("index.html");
    const std::string script = page_text("viewer.js");
    const std::string style = page_text("viewer.css");
    const std::string icon = page_text("favicon.ico");
    check_inline(script, "viewer.js", "</script");
    check_inline(style, "viewer.css", "</style");
    render::OpenedRun run = render::open_run_directory(o.run_dir, render::SourceKind::automatic);
    render::FrameSource& source = *run.source;
    const std::size_t frames = source.frames();
    std::vector<std::size_t> chosen;
    for (std::size_t k = 0; k < frames; k += std::max<std::size_t>(o.every, 1)) chosen.push_back(k);
    if (chosen.back() != frames - 1) chosen.push_back(frames - 1);

    const render::Frame first = source.frame(0);
    std::vector<Field> fields = {Field::position, Field::species, Field::radius};
    if (frame_has(first, Field::director)) fields.push_back(Field::director);
    // to colour by: speed, angle and the file's own columns; the velocity components, the
    // energy, mass and id would double the page's size (the served page has them)
    std::vector<std::string> colour_by = colour_fields(first);
    std::erase_if(colour_by, [](const std::string& name) {
        return name == "vx" || name == "vy" || name == "vz" || name == "kinetic_energy" ||
               name == "mass" || name == "id" || name == "radius"; // (radius: a field)
    });
    // 4 bytes a number: 3 + 1 + 1 for position, species and radius, 3 for a director, 1
    // for each number to colour by; base64 makes 4 of every 3
    const std::uint64_t numbers =
        5 + (frame_has(first, Field::director) ? 3 : 0) + colour_by.size();
    const std::uint64_t estimate = chosen.size() * first.size() * numbers * 4 * 4 / 3;
    if (estimate > o.max_bytes) {
        const std::uint64_t per_frame = std::max<std::uint64_t>(estimate / chosen.size(), 1);
        const std::uint64_t fit = std::max<std::uint64_t>(o.max_bytes / per_frame, 1);
        throw InputError(fmt::format(
            "pedesis view --export: {} frames of {} particles would make a page of about {} MB, "
            "more than the {} MB a browser opens comfortably; keep fewer frames with --every {} "
            "({} frames)",
            chosen.size(), first.size(), estimate >> 20, o.max_bytes >> 20,
            (frames + fit - 1) / fit, fit));
    }

    nlohmann::json data;
    data["info"] = run_info(source, first, o.run_dir);
    // a file to share names no path of this machine: the run directory's and the trajectory
    // file's own names only ("trajectory.xyz (extended XYZ)")
    data["info"]["run"] = base_name(std::filesystem::absolute(o.run_dir));
    {
        const std::string described = source.description(); // "PATH (KIND)"
        const auto kind = described.rfind(" (");
        data["info"]["source"] =
            base_name(described.substr(0, kind)) +
            (kind == std::string::npos ? std::string() : described.substr(kind));
    }
    data["info"]["frames"] = chosen.size();
    data["info"]["colour_by"] = colour_by;
    data["info"]["colour_by"].push_back("radius");
    data["log"] = read_log(o.run_dir);
    nlohmann::json& out = data["frames"];
    out = nlohmann::json::array();
    for (const std::size_t k : chosen) {
        const render::Frame f = source.frame(k);
        nlohmann::json frame = {{"index", k},
                                {"time", f.time ? nlohmann::json(*f.time) : nlohmann::json()},
                                {"step", f.step ? nlohmann::json(*f.step) : nlohmann::json()}};
        const auto lacks = [&](std::string_view what) {
            return InputError(fmt::format("pedesis view --export: frame {} of {} lacks the {} "
                                          "that frame 0 has",
                                          k, source.description(), what));
        };
        for (const Field field : fields) {
            if (!frame_has(f, field)) throw lacks(field_name(field));
            frame[std::string(field_name(field))] = base64(frame_bytes(f, field));
        }
        for (const std::string& name : colour_by) {
            const std::optional<std::string> bytes = colour_field_bytes(f, name);
            if (!bytes) throw lacks(name);
            frame[name] = base64(*bytes);
        }
        out.push_back(std::move(frame));
    }
    // The run travels as data, not as a script: a JSON block that the browser never runs,
    // read by the bundle (JSON.parse), with no '<' in it (json_for_html). The policy lets
    // only the bundle run and only the style apply, by their SHA-256 computed when the page
    // was built (web/viewer/CMakeLists.txt), and nothing load from anywhere (images only
    // from data: and blob: addresses: the icon, the screenshot).
    const std::string policy =
        fmt::format("default-src 'none'; script-src '{}'; style-src '{}'; img-src data: blob:; "
                    "base-uri 'none'; form-action 'none'",
                    page_text("viewer.js.sha256"), page_text("viewer.css.sha256"));
    replace_once(
        html, "<meta charset=\"utf-8\">",
        "<meta charset=\"utf-8\">\n<meta http-equiv=\"Content-Security-Policy\" content=\"" +
            policy + "\">");
    replace_once(html, "<link rel=\"icon\" href=\"favicon.ico\" type=\"image/svg+xml\">",
                 "<link rel=\"icon\" href=\"data:image/svg+xml;base64," + base64(icon) + "\">");
    replace_once(html, "<link rel=\"stylesheet\" href=\"viewer.css\">",
                 "<style>" + style + "</style>");
    replace_once(html, "<script src=\"viewer.js\"></script>",
                 "<script type=\"application/json\" id=\"pedesis-export\">" + json_for_html(data) +
                     "</script>\n<script>" + script + "</script>");
    write_file_atomically(o.output, [&](std::ostream& file) { file << html; });
}

} // namespace pedesis::view
