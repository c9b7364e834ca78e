// SPDX-License-Identifier: Apache-2.0
// The UTF-8 helpers against two independent references: hand-picked vectors from Markus Kuhn's UTF-8 decoder
// stress test with the valid prefix Python's strict decoder reports (bytes.decode("utf-8"): UnicodeDecodeError.start),
// and glibc's mbrtowc in C.UTF-8 over every sequence of up to three bytes and every four-byte lead.
#include "base/utf8.h"

#include <clocale>
#include <cwchar>
#include <string>

#include <gtest/gtest.h>

using namespace overlayd;
using namespace std::string_view_literals;

namespace {

struct Vector {
    const char *name;
    std::string_view bytes;
    size_t validPrefix; // Python: len(bytes) when it decodes, else UnicodeDecodeError.start
};

// Generated with Python 3.11's decoder from the byte strings of the stress test's sections 1-5.
const Vector kKuhnVectors[] = {
    {"kosme", "\xCE\xBA\xEF\xBD\xB9\xCF\x83\xCE\xBC\xCE\xB5"sv, 11},
    {"first 1 byte (NUL)", "\x00"sv, 1},
    {"first 2 bytes U+0080", "\xC2\x80"sv, 2},
    {"first 3 bytes U+0800", "\xE0\xA0\x80"sv, 3},
    {"first 4 bytes U+10000", "\xF0\x90\x80\x80"sv, 4},
    {"first 5 bytes", "\xF8\x88\x80\x80\x80"sv, 0},
    {"first 6 bytes", "\xFC\x84\x80\x80\x80\x80"sv, 0},
    {"last 1 byte U+007F", "\x7F"sv, 1},
    {"last 2 bytes U+07FF", "\xDF\xBF"sv, 2},
    {"last 3 bytes U+FFFF", "\xEF\xBF\xBF"sv, 3},
    {"U+10FFFF", "\xF4\x8F\xBF\xBF"sv, 4},
    {"U+110000", "\xF4\x90\x80\x80"sv, 0},
    {"U+D7FF", "\xED\x9F\xBF"sv, 3},
    {"U+E000", "\xEE\x80\x80"sv, 3},
    {"U+FFFD", "\xEF\xBF\xBD"sv, 3},
    {"lone continuation 80", "\x80"sv, 0},
    {"lone continuation BF", "\xBF"sv, 0},
    {"two continuations", "\x80\xBF"sv, 0},
    {"lonely start C0 space", "\xC0\x20"sv, 0},
    {"lonely start E0 space", "\xE0\x20"sv, 0},
    {"lonely start F0 space", "\xF0\x20"sv, 0},
    {"2-byte missing last", "\xC2"sv, 0},
    {"3-byte missing last", "\xE0\x80"sv, 0},
    {"4-byte missing last", "\xF0\x80\x80"sv, 0},
    {"DF missing last", "\xDF"sv, 0},
    {"EF BF missing last", "\xEF\xBF"sv, 0},
    {"F4 8F BF missing last", "\xF4\x8F\xBF"sv, 0},
    {"FE", "\xFE"sv, 0},
    {"FF", "\xFF"sv, 0},
    {"FE FE FF FF", "\xFE\xFE\xFF\xFF"sv, 0},
    {"overlong / 2", "\xC0\xAF"sv, 0},
    {"overlong / 3", "\xE0\x80\xAF"sv, 0},
    {"overlong / 4", "\xF0\x80\x80\xAF"sv, 0},
    {"max overlong 2", "\xC1\xBF"sv, 0},
    {"max overlong 3", "\xE0\x9F\xBF"sv, 0},
    {"max overlong 4", "\xF0\x8F\xBF\xBF"sv, 0},
    {"overlong NUL 2", "\xC0\x80"sv, 0},
    {"overlong NUL 3", "\xE0\x80\x80"sv, 0},
    {"surrogate D800", "\xED\xA0\x80"sv, 0},
    {"surrogate DB7F", "\xED\xAD\xBF"sv, 0},
    {"surrogate DB80", "\xED\xAE\x80"sv, 0},
    {"surrogate DBFF", "\xED\xAF\xBF"sv, 0},
    {"surrogate DC00", "\xED\xB0\x80"sv, 0},
    {"surrogate DF80", "\xED\xBE\x80"sv, 0},
    {"surrogate DFFF", "\xED\xBF\xBF"sv, 0},
    {"paired surrogates", "\xED\xA0\x80\xED\xB0\x80"sv, 0},
    {"noncharacter U+FFFE", "\xEF\xBF\xBE"sv, 3},
    {"F5 above U+10FFFF", "\xF5\x80\x80\x80"sv, 0},
    {"valid then invalid", "\x61\xC3\xA9\x62\xFF\x63"sv, 4},
    {"valid then cut", "\x61\x62\x63\xE2\x82"sv, 3},
};

// glibc's answer for the sequence at the start of text: its length, 0 when invalid or incomplete. glibc also takes
// code points above U+10FFFF (the old five- and six-byte forms): RFC 3629 does not, so they count as invalid here.
size_t mbrtowcLength(std::string_view text)
{
    std::mbstate_t state{};
    wchar_t wide = 0;
    const size_t got = std::mbrtowc(&wide, text.data(), text.size(), &state);
    if (got == size_t(-1) || got == size_t(-2) || wide > 0x10FFFF)
        return 0;
    return got == 0 ? 1 : got; // 0: the NUL character, one byte
}

class Utf8AgainstMbrtowc : public ::testing::Test
{
protected:
    void SetUp() override
    {
        if (!std::setlocale(LC_CTYPE, "C.UTF-8"))
            GTEST_SKIP() << "no C.UTF-8 locale";
    }
    void TearDown() override { std::setlocale(LC_CTYPE, "C"); }
};

} // namespace

TEST(Utf8, ValidPrefixMatchesPythonOnKuhnsStressTest)
{
    for (const Vector &vector : kKuhnVectors) {
        EXPECT_EQ(validUtf8Prefix(vector.bytes), vector.validPrefix) << vector.name;
        EXPECT_EQ(isValidUtf8(vector.bytes), vector.validPrefix == vector.bytes.size()) << vector.name;
    }
}

TEST_F(Utf8AgainstMbrtowc, EverySequenceOfUpToThreeBytes)
{
    for (unsigned a = 0; a < 256; ++a) {
        for (unsigned b = 0; b < 256; ++b) {
            for (unsigned c = 0; c < 256; ++c) {
                const char bytes[] = {char(a), char(b), char(c)};
                const std::string_view text(bytes, 3);
                ASSERT_EQ(utf8SequenceLength(text, 0), mbrtowcLength(text)) << std::hex << a << ' ' << b << ' ' << c;
            }
        }
    }
}

TEST_F(Utf8AgainstMbrtowc, EveryFourByteLead)
{
    for (unsigned a = 0xF0; a < 0x100; ++a)
        for (unsigned b = 0; b < 256; ++b)
            for (unsigned c : {0x00u, 0x80u, 0x9Fu, 0xBFu, 0xC0u})
                for (unsigned d : {0x41u, 0x80u, 0xBFu, 0xC0u}) {
                    const char bytes[] = {char(a), char(b), char(c), char(d)};
                    const std::string_view text(bytes, 4);
                    ASSERT_EQ(utf8SequenceLength(text, 0), mbrtowcLength(text))
                        << std::hex << a << ' ' << b << ' ' << c << ' ' << d;
                }
}

TEST(Utf8, CutsOnlyOnCharacterBoundaries)
{
    const std::string_view text = "a\xC3\xA9\xE2\x82\xAC\xF0\x9F\x98\x80"sv; // a é € 😀: 1 + 2 + 3 + 4 bytes
    const size_t expected[] = {0, 1, 1, 3, 3, 3, 6, 6, 6, 6, 10, 10};
    for (size_t max = 0; max < std::size(expected); ++max)
        EXPECT_EQ(utf8Cut(text, max), expected[max]) << "max " << max;
}

TEST(Utf8, OutsideTextProblemNamesTheFirstByte)
{
    EXPECT_EQ(outsideTextProblem("50 km/h \xC3\xA9"), std::nullopt);
    EXPECT_EQ(outsideTextProblem("ab\xFF"), "not valid UTF-8 at byte 2");
    EXPECT_EQ(outsideTextProblem("ab\xED\xA0\x80"), "not valid UTF-8 at byte 2"); // a surrogate
    EXPECT_EQ(outsideTextProblem("a\tb"), "a control character (U+0009) at byte 1");
    EXPECT_EQ(outsideTextProblem("a\tb", "\t"), std::nullopt);
    EXPECT_EQ(outsideTextProblem("a\x7F"), "a control character (U+007F) at byte 1");
    EXPECT_EQ(outsideTextProblem("a\xC2\x85"), "a control character (U+0085) at byte 1"); // C1: NEL
    EXPECT_EQ(outsideTextProblem("a\xC2\x85", "\x85"), "a control character (U+0085) at byte 1");
    EXPECT_EQ(outsideTextProblem("\xC2\xA0"), std::nullopt); // U+00A0, the first after C1
}

TEST(Utf8, QuotableIsValidUtf8AndKeepsWholeCharacters)
{
    EXPECT_EQ(quotable("1.5m", 32), "1.5m");
    EXPECT_EQ(quotable("a\xFF\x01z", 32), "a\\xFF\\x01z");
    EXPECT_EQ(quotable("ab\xED\xA0\x80", 32), "ab\\xED\\xA0\\x80");
    // Cut after 3 bytes: the € (E2 82 AC) that starts at byte 2 is dropped whole, never half of it.
    EXPECT_EQ(quotable("ab\xE2\x82\xAC", 3), "ab...");
    EXPECT_EQ(quotable("ab\xE2\x82\xAC", 5), "ab\xE2\x82\xAC");
    for (const Vector &vector : kKuhnVectors)
        for (size_t max = 0; max <= vector.bytes.size(); ++max)
            EXPECT_TRUE(isValidUtf8(quotable(vector.bytes, max))) << vector.name << " cut at " << max;
}
