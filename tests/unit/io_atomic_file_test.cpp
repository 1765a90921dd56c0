// Output files are complete or absent: failures leave nothing behind, and a
// trajectory only gets its final name once the run commits it.
#include "pedesis/core/error.hpp"
#include "pedesis/io/atomic_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;
using pedesis::AtomicAppendFile;
using pedesis::InputError;
using pedesis::RunError;
using pedesis::write_file_atomically;

namespace {

// A fresh, empty directory per test, so that "nothing else is there" is checkable.
class io_atomic_file : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::temp_directory_path() /
              ("pedesis_io_atomic_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }

    std::set<std::string> listing() const {
        std::set<std::string> names;
        for (const auto& e : fs::directory_iterator(dir))
            names.insert(e.path().filename().string());
        return names;
    }

    fs::path dir;
};

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void write_text(const fs::path& p, const std::string& text) {
    std::ofstream(p, std::ios::binary) << text;
}

} // namespace

TEST_F(io_atomic_file, WritesTheWholeBodyAndLeavesNoTemporary) {
    const fs::path file = dir / "out.json";
    write_file_atomically(file, [](std::ostream& out) { out << "hello\n" << 42; });
    EXPECT_EQ(slurp(file), "hello\n42");
    EXPECT_EQ(listing(), std::set<std::string>{"out.json"});
}

TEST_F(io_atomic_file, BinaryModeWritesBytesExactly) {
    const fs::path file = dir / "out.bin";
    const std::string bytes("a\0b\r\n\xff", 6);
    write_file_atomically(
        file, [&](std::ostream& out) { out.write(bytes.data(), 6); }, true);
    EXPECT_EQ(slurp(file), bytes);
}

TEST_F(io_atomic_file, ReplacesAnExistingFile) {
    const fs::path file = dir / "out.txt";
    write_text(file, "old contents that are longer than the new ones");
    write_file_atomically(file, [](std::ostream& out) { out << "new"; });
    EXPECT_EQ(slurp(file), "new");
    EXPECT_EQ(listing(), std::set<std::string>{"out.txt"});
}

TEST_F(io_atomic_file, BodyInputErrorPassesThroughAndLeavesNoFile) {
    const fs::path file = dir / "out.txt";
    try {
        write_file_atomically(file, [](std::ostream& out) {
            out << "half a file";
            throw InputError("particle 7: bad radius");
        });
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "particle 7: bad radius");
    }
    EXPECT_TRUE(listing().empty());
}

TEST_F(io_atomic_file, BodyRunErrorPassesThroughUnchanged) {
    const fs::path file = dir / "out.txt";
    EXPECT_THROW(write_file_atomically(file,
                                       [](std::ostream& out) {
                                           out << "x";
                                           throw RunError("inelastic collapse");
                                       }),
                 RunError);
    EXPECT_TRUE(listing().empty());
}

TEST_F(io_atomic_file, FailureKeepsThePreviousFileUntouched) {
    const fs::path file = dir / "out.txt";
    write_text(file, "previous");
    EXPECT_THROW(write_file_atomically(file,
                                       [](std::ostream& out) {
                                           out << "partial";
                                           throw std::runtime_error("boom");
                                       }),
                 InputError);
    EXPECT_EQ(slurp(file), "previous");
    EXPECT_EQ(listing(), std::set<std::string>{"out.txt"});
}

TEST_F(io_atomic_file, OtherExceptionsBecomeInputErrorNamingThePath) {
    const fs::path file = dir / "named.txt";
    try {
        write_file_atomically(file,
                              [](std::ostream&) { throw std::runtime_error("disk on fire"); });
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("disk on fire"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(listing().empty());
}

TEST_F(io_atomic_file, StreamErrorIsReportedAndLeavesNoFile) {
    const fs::path file = dir / "out.txt";
    try {
        write_file_atomically(file, [](std::ostream& out) {
            out << "data";
            out.setstate(std::ios::badbit); // what a failed write (disk full) does
        });
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
    EXPECT_TRUE(listing().empty());
}

TEST_F(io_atomic_file, UnwritableDirectoryIsAnInputErrorNamingThePath) {
    const fs::path file = dir / "no" / "such" / "dir" / "out.txt";
    try {
        write_file_atomically(file, [](std::ostream& out) { out << "x"; });
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
    EXPECT_TRUE(listing().empty());
}

TEST_F(io_atomic_file, AppendWithoutCommitLeavesOnlyThePartFile) {
    const fs::path file = dir / "traj.xyz";
    {
        AtomicAppendFile traj(file);
        traj.append("frame 1\n");
        traj.append("frame 2\n");
        // The frames are on disk while the run is still going.
        EXPECT_EQ(slurp(dir / "traj.xyz.part"), "frame 1\nframe 2\n");
        traj.append("frame 3\n");
    } // a run that ends without commit (killed, crashed)
    EXPECT_EQ(listing(), std::set<std::string>{"traj.xyz.part"});
    EXPECT_EQ(slurp(dir / "traj.xyz.part"), "frame 1\nframe 2\nframe 3\n");
}

TEST_F(io_atomic_file, CommitLeavesOnlyTheFinalFileWithAllFrames) {
    const fs::path file = dir / "traj.xyz";
    {
        AtomicAppendFile traj(file);
        traj.append("frame 1\n");
        traj.append("frame 2\n");
        traj.commit();
        traj.commit(); // harmless a second time
        EXPECT_TRUE(traj.committed());
    }
    EXPECT_EQ(listing(), std::set<std::string>{"traj.xyz"});
    EXPECT_EQ(slurp(file), "frame 1\nframe 2\n");
}

TEST_F(io_atomic_file, AStaleCompleteFileDoesNotOutliveAnUncommittedRun) {
    const fs::path file = dir / "traj.xyz";
    write_text(file, "from an earlier run\n");
    write_text(dir / "traj.xyz.part", "torn frame from an earlier run");
    {
        AtomicAppendFile traj(file);
        traj.append("new frame\n");
    }
    EXPECT_EQ(listing(), std::set<std::string>{"traj.xyz.part"});
    EXPECT_EQ(slurp(dir / "traj.xyz.part"), "new frame\n");
}

TEST_F(io_atomic_file, AppendFileInMissingDirectoryIsAnInputError) {
    const fs::path file = dir / "missing" / "traj.xyz";
    try {
        AtomicAppendFile traj(file);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
}
