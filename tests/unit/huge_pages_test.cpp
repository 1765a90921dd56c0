// back_with_huge_pages is advice: whatever the kernel does with it (collapse the pages,
// keep them small, refuse), the memory must hold the same bytes afterwards, including
// the parts of the range outside the whole huge pages and memory just beyond it.
#include "pedesis/core/huge_pages.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

using namespace pedesis;

namespace {

std::uint64_t pattern(std::size_t k) {
    return k * 0x9e3779b97f4a7c15ull ^ (k >> 7);
}

std::vector<std::uint64_t> filled(std::size_t n) {
    std::vector<std::uint64_t> v(n);
    for (std::size_t k = 0; k < n; ++k) v[k] = pattern(k);
    return v;
}

void expect_pattern(const std::vector<std::uint64_t>& v, std::size_t from, std::size_t to) {
    std::size_t wrong = 0;
    for (std::size_t k = from; k < to; ++k) wrong += v[k] != pattern(k);
    EXPECT_EQ(wrong, 0u) << "in [" << from << ", " << to << ")";
}

} // namespace

TEST(HugePages, ContentsSurviveTheAdvice) {
    // 24 MiB and a bit: several whole huge pages, and ends that are not aligned to them
    auto v = filled((24u << 20) / 8 + 1234);
    back_with_huge_pages(v);
    expect_pattern(v, 0, v.size());
    // and writes afterwards land where they should
    for (std::size_t k = 0; k < v.size(); k += 4093) v[k] = ~pattern(k);
    for (std::size_t k = 0; k < v.size(); k += 4093) ASSERT_EQ(v[k], ~pattern(k));
}

TEST(HugePages, APartOfABufferLeavesTheRestAsItWas) {
    auto v = filled((12u << 20) / 8);
    // the middle third, starting off any page boundary
    const std::size_t from = v.size() / 3 + 5, to = 2 * v.size() / 3;
    back_with_huge_pages(v.data() + from, (to - from) * sizeof(std::uint64_t));
    expect_pattern(v, 0, v.size());
}

TEST(HugePages, RangesSmallerThanAHugePageAndEmptyOnesAreLeftAlone) {
    auto v = filled(1000);
    back_with_huge_pages(v);
    back_with_huge_pages(v.data(), 0);
    back_with_huge_pages(nullptr, 1u << 22);
    std::vector<double> empty;
    back_with_huge_pages(empty);
    expect_pattern(v, 0, v.size());
}

TEST(HugePages, TheCountOfHugePageBytesIsAWholeNumberOfPages) {
    // AnonHugePages is reported in kB, in whole 2 MiB pages (0 where THP is off)
    EXPECT_EQ(huge_page_bytes() % (2u << 20), 0u);
}
