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

#include <optional>
#include <sstream>

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

} // namespace

void export_page(const ExportOptions& o) {
    std::string html = page_text("index.html");
    const std::string script = page_text("viewer.js");
    const std::string style = page_text("viewer.css");
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
    // (no "</" can end the script early: JSON text here is numbers, names and base64,
    // and a name's "</" is written "<\/")
    std::string json = data.dump();
    for (auto at = json.find("</"); at != std::string::npos; at = json.find("</", at + 3))
        json.replace(at, 2, "<\\/");
    replace_once(html, "<link rel=\"stylesheet\" href=\"viewer.css\">",
                 "<style>" + style + "</style>");
    replace_once(html, "<script src=\"viewer.js\"></script>",
                 "<script>window.PEDESIS_EXPORT = " + json + ";</script>\n<script>" + script +
                     "</script>");
    write_file_atomically(o.output, [&](std::ostream& file) { file << html; });
}

} // namespace pedesis::view
