#include "pedesis/io/resume_record.hpp"

#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <bit>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <system_error>

namespace pedesis {

namespace {

constexpr int record_version = 1;
constexpr std::uintmax_t largest_record = 1u << 20;

nlohmann::json to_json(const OutputMarks& m) {
    const GsdMark& g = m.frames.gsd;
    return {{"step", m.step},
            {"time", m.time},
            {"time_bits", std::bit_cast<std::uint64_t>(m.time)},
            {"final", m.final},
            {"log_bytes", m.log_bytes},
            {"frames", m.frames.frames},
            {"xyz_bytes", m.frames.xyz_bytes},
            {"gsd",
             {{"file_end", g.file_end},
              {"index_location", g.index_location},
              {"index_capacity", g.index_capacity},
              {"index_entries", g.index_entries},
              {"frames", g.frames},
              {"first_types", g.first_types}}}};
}

template <class T> T field(const nlohmann::json& j, const char* key) {
    if (!j.is_object() || !j.contains(key)) throw InputError(std::string("no \"") + key + "\"");
    const nlohmann::json& v = j.at(key);
    if constexpr (std::is_same_v<T, bool>) {
        if (!v.is_boolean()) throw InputError(std::string("\"") + key + "\" is not true or false");
    } else {
        if (!v.is_number_unsigned())
            throw InputError(std::string("\"") + key + "\" is not a count");
    }
    return v.get<T>();
}

OutputMarks from_json(const nlohmann::json& j) {
    OutputMarks m;
    m.step = field<std::uint64_t>(j, "step");
    m.time = std::bit_cast<double>(field<std::uint64_t>(j, "time_bits"));
    m.final = field<bool>(j, "final");
    m.log_bytes = field<std::uint64_t>(j, "log_bytes");
    m.frames.frames = field<std::uint64_t>(j, "frames");
    m.frames.xyz_bytes = field<std::uint64_t>(j, "xyz_bytes");
    if (!j.contains("gsd")) throw InputError("no \"gsd\"");
    const nlohmann::json& g = j.at("gsd");
    m.frames.gsd.file_end = field<std::uint64_t>(g, "file_end");
    m.frames.gsd.index_location = field<std::uint64_t>(g, "index_location");
    m.frames.gsd.index_capacity = field<std::uint64_t>(g, "index_capacity");
    m.frames.gsd.index_entries = field<std::uint64_t>(g, "index_entries");
    m.frames.gsd.frames = field<std::uint64_t>(g, "frames");
    if (!g.contains("first_types") || !g.at("first_types").is_array())
        throw InputError("no \"first_types\" list");
    for (const auto& t : g.at("first_types")) {
        if (!t.is_string()) throw InputError("a type name is not a string");
        m.frames.gsd.first_types.push_back(t.get<std::string>());
    }
    return m;
}

} // namespace

bool marks_at(const OutputMarks& m, std::uint64_t step, double time) {
    return m.step == step &&
           std::bit_cast<std::uint64_t>(m.time) == std::bit_cast<std::uint64_t>(time);
}

void write_checkpoint_record(const std::filesystem::path& file,
                             const std::vector<OutputMarks>& marks) {
    nlohmann::json j = {{"pedesis_checkpoint_record", record_version},
                        {"checkpoints", nlohmann::json::array()}};
    for (const OutputMarks& m : marks) j["checkpoints"].push_back(to_json(m));
    write_file_atomically(file, [&](std::ostream& out) { out << j.dump(1) << "\n"; });
    sync_file(file);
}

std::vector<OutputMarks> read_checkpoint_record(const std::filesystem::path& file) {
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(file, ec);
    if (ec) throw InputError(file.string() + ": cannot read it: " + ec.message());
    if (size > largest_record)
        throw InputError(file.string() + ": over 1 MiB, not a checkpoint record of pedesis");
    std::ifstream in(file, std::ios::binary);
    const std::string text{std::istreambuf_iterator<char>(in), {}};
    try {
        const nlohmann::json j = nlohmann::json::parse(text);
        if (!j.is_object() || j.value("pedesis_checkpoint_record", 0) != record_version)
            throw InputError("not a checkpoint record of this pedesis (version 1)");
        if (!j.contains("checkpoints") || !j.at("checkpoints").is_array())
            throw InputError("no \"checkpoints\" list");
        std::vector<OutputMarks> marks;
        for (const auto& entry : j.at("checkpoints")) marks.push_back(from_json(entry));
        return marks;
    } catch (const nlohmann::json::exception& e) {
        throw InputError(file.string() + ": not a checkpoint record (" + e.what() + ")");
    } catch (const InputError& e) {
        throw InputError(file.string() + ": " + e.what());
    }
}

} // namespace pedesis
