// The GL backend's recorded lists (CommandStream): records come back in order with their
// payloads, across block boundaries and for records larger than a block, and a reset stream
// records again into the same memory.
#include <gtest/gtest.h>

#include <cstddef>
#include <limits>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "fe/gdi/CaptureStream.h"
#include "fe/gdi/CommandStream.h"
#include "fe/gdi/MessageLog.h"

using namespace fe::gdi;

namespace {

// What forEach gives back, as text: one entry per record.
std::vector<std::string> replayed(const cmd::CommandStream& s) {
    std::vector<std::string> out;
    s.forEach([&](const auto& r) {
        using R = std::decay_t<decltype(r)>;
        std::string line = R::kName;
        if constexpr (std::is_same_v<R, cmd::Draw>) line += " " + std::to_string(r.vertexCount);
        if constexpr (std::is_same_v<R, cmd::PushDebugGroup>)
            line += " " + std::string(cmd::view(r, r.name));
        if constexpr (std::is_same_v<R, cmd::BufferBarriers>)
            line += " " + std::to_string(cmd::view(r, r.barriers).size()) + "@" +
                    std::to_string(cmd::view(r, r.barriers).back().offset);
        out.push_back(line);
    });
    return out;
}

void pushName(cmd::CommandStream& s, const char* name) {
    auto* r = s.push(cmd::PushDebugGroup{}, cmd::CommandStream::payloadSize(name));
    r->name = s.payload(*r, name);
}

}  // namespace

TEST(CommandStream, RecordsComeBackInOrderAcrossBlocks) {
    cmd::CommandStream s;
    std::vector<std::string> expected;
    for (uint32_t i = 0; i < 20000; ++i) {  // ~0.5 MiB: several 64 KiB blocks
        if (i % 1000 == 0) {
            const std::string name = "group " + std::to_string(i);
            pushName(s, name.c_str());
            expected.push_back("PushDebugGroup " + name);
        }
        s.push(cmd::Draw{.vertexCount = i});
        expected.push_back("Draw " + std::to_string(i));
    }
    // A record whose payload alone is larger than a block.
    std::vector<BufferBarrier> many(5000);
    for (size_t i = 0; i < many.size(); ++i) many[i].offset = i;
    auto* r = s.push(cmd::BufferBarriers{},
                     cmd::CommandStream::payloadSize(many.size() * sizeof(BufferBarrier)));
    r->barriers = s.payload(*r, std::span<const BufferBarrier>(many));
    expected.push_back("BufferBarriers 5000@4999");
    s.push(cmd::EndRenderPass{});
    expected.push_back("EndRenderPass");
    EXPECT_EQ(s.commandCount(), expected.size());
    EXPECT_EQ(replayed(s), expected);

    s.reset();
    EXPECT_TRUE(s.empty());
    EXPECT_TRUE(replayed(s).empty()) << "a reset stream still replays old records";
    s.push(cmd::Draw{.vertexCount = 7});
    pushName(s, "again");
    EXPECT_EQ(replayed(s), (std::vector<std::string>{"Draw 7", "PushDebugGroup again"}));
}

TEST(CommandStream, EveryCommandHasANameAndFields) {
    EXPECT_STREQ(cmd::opName(cmd::Op::Draw), "Draw");
    EXPECT_STREQ(cmd::opName(cmd::Op::BufferBarriers), "BufferBarriers");
    std::vector<std::string> fields;
    cmd::forEachField(cmd::SetUniformBuffer{.slot = 3},
                      [&](const char* name, const auto&) { fields.push_back(name); });
    EXPECT_EQ(fields, (std::vector<std::string>{"slot", "buffer", "offset", "size"}));
}

// A primary stream adopts a secondary list's stream whole; ExecuteSecondary names it, reset
// drops it, and takeChildren hands the adopted streams back for reuse.
TEST(CommandStream, AdoptsSecondaryStreams) {
    cmd::CommandStream primary;
    auto secondary = std::make_unique<cmd::CommandStream>();
    secondary->push(cmd::Draw{.vertexCount = 5});
    const cmd::CommandStream* adopted = secondary.get();
    primary.push(cmd::ExecuteSecondary{primary.adopt(std::move(secondary))});
    std::vector<std::string> seen;
    primary.forEach([&](const auto& record) {
        using R = std::decay_t<decltype(record)>;
        if constexpr (std::is_same_v<R, cmd::ExecuteSecondary>) {
            EXPECT_EQ(&primary.child(record.child), adopted);
            seen.push_back("ExecuteSecondary " +
                           std::to_string(replayed(primary.child(record.child)).size()));
        }
    });
    EXPECT_EQ(seen, (std::vector<std::string>{"ExecuteSecondary 1"}));
    auto back = primary.takeChildren();
    ASSERT_EQ(back.size(), 1u);
    EXPECT_EQ(back[0].get(), adopted);
    EXPECT_THROW(primary.child(0), std::out_of_range);
}

// Validation messages: each distinct one printed once, every report counted.
TEST(MessageLog, PrintsEachMessageOnceAndCountsRepeats) {
    fe::gdi::MessageLog log("test");
    ::testing::internal::CaptureStderr();
    for (int i = 0; i < 60; ++i) log.report("error", "the same mistake every frame");
    log.report("warning", "the same mistake every frame");
    log.report("error", "another one");
    const std::string printed = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(log.count("error", "the same mistake every frame"), 60u);
    EXPECT_EQ(log.count("warning", "the same mistake every frame"), 1u);
    EXPECT_EQ(log.distinct(), 3u);
    size_t lines = 0;
    for (char c : printed) lines += c == '\n';
    EXPECT_EQ(lines, 3u) << printed;
    ::testing::internal::CaptureStderr();
    log.printRepeats();
    const std::string repeats = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(
        repeats.find("test message repeated 60 times in all: error: the same mistake every frame"),
        std::string::npos)
        << repeats;
    EXPECT_EQ(repeats.find("another one"), std::string::npos);
}

// Capture form (CaptureStream.h): a stream with payloads, strings and a secondary stream comes
// back from its bytes record for record, and re-encodes to the same bytes.
namespace {
std::unique_ptr<cmd::CommandStream> sampleStream() {
    auto s = std::make_unique<cmd::CommandStream>();
    pushName(*s, "frame");
    s->push(cmd::Draw{.vertexCount = 3, .instanceCount = 1});
    std::vector<BufferBarrier> barriers(3, BufferBarrier{.offset = 16});
    auto* b = s->push(cmd::BufferBarriers{},
                      cmd::CommandStream::payloadSize(barriers.size() * sizeof(BufferBarrier)));
    b->barriers = s->payload(*b, std::span<const BufferBarrier>(barriers));
    auto child = std::make_unique<cmd::CommandStream>();
    child->push(cmd::Draw{.vertexCount = 7});
    s->push(cmd::ExecuteSecondary{s->adopt(std::move(child))});
    s->push(cmd::PopDebugGroup{});
    return s;
}
}  // namespace

TEST(CaptureStream, RoundTripsRecordsPayloadsAndSecondaryStreams) {
    const auto s = sampleStream();
    const std::vector<std::byte> bytes = encodeCommandStream(*s);
    const auto back = decodeCommandStream(bytes);
    EXPECT_EQ(replayed(*back), replayed(*s));
    EXPECT_EQ(replayed(back->child(0)), (std::vector<std::string>{"Draw 7"}));
    EXPECT_EQ(encodeCommandStream(*back), bytes);
}

// Hostile bytes: every truncation, and every single-byte change, either decodes or is refused
// with a CaptureError naming the offset; never a crash (the sanitizer builds run this too).
TEST(CaptureStream, RefusesTruncatedAndDamagedBytesNamingTheOffset) {
    const std::vector<std::byte> bytes = encodeCommandStream(*sampleStream());
    for (size_t n = 0; n < bytes.size(); ++n) {
        try {
            decodeCommandStream(std::span(bytes).first(n));
            ADD_FAILURE() << "a stream cut to " << n << " of " << bytes.size()
                          << " bytes was accepted";
        } catch (const CaptureError& e) {
            EXPECT_NE(std::string(e.what()).find("offset"), std::string::npos) << e.what();
        }
    }
    size_t refused = 0;
    for (size_t i = 0; i < bytes.size(); ++i) {
        std::vector<std::byte> damaged = bytes;
        damaged[i] ^= std::byte{0xff};
        try {
            decodeCommandStream(damaged);
        } catch (const CaptureError&) {
            ++refused;
        }
    }
    EXPECT_GT(refused,
              bytes.size() / 4);  // headers, sizes, ops, offsets and string ends are checked
    // Specific refusals name what is wrong.
    std::vector<std::byte> badOp = bytes;
    const uint16_t op = 999;
    std::memcpy(&badOp[16], &op, 2);  // the first record's opcode, after the 16-byte stream header
    EXPECT_THROW(
        {
            try {
                decodeCommandStream(badOp);
            } catch (const CaptureError& e) {
                EXPECT_NE(std::string(e.what()).find("record 0 at offset 16: unknown command 999"),
                          std::string::npos)
                    << e.what();
                throw;
            }
        },
        CaptureError);
}

// Field values a device could not be handed safely are refused when read: a bool of 3, an enum
// out of range, flags beyond their bits, a NaN (found by the capture-file fuzzer: a bool of 3
// reached the replay, undefined behaviour to load).
TEST(CaptureStream, RefusesValuesNoDeviceCouldBeHanded) {
    auto refusal = [](auto record, auto damage) {
        cmd::CommandStream s;
        s.push(record);
        std::vector<std::byte> bytes = encodeCommandStream(s);
        damage(bytes.data() + 16 + sizeof(cmd::CommandStream::Header));  // the record's fields
        try {
            decodeCommandStream(bytes);
        } catch (const CaptureError& e) {
            return std::string(e.what());
        }
        return std::string("(accepted)");
    };
    EXPECT_NE(
        refusal(cmd::SetAutomaticBarriers{true}, [](std::byte* f) { f[0] = std::byte(3); })
            .find("(SetAutomaticBarriers) at offset 16: field 'enabled' is not a boolean (3)"),
        std::string::npos);
    EXPECT_NE(refusal(cmd::SetIndexBuffer{},
                      [](std::byte* f) { f[offsetof(cmd::SetIndexBuffer, type)] = std::byte(9); })
                  .find("field 'type' has no such value (9)"),
              std::string::npos);
    EXPECT_NE(refusal(cmd::SetViewport{},
                      [](std::byte* f) {
                          const float nan = std::numeric_limits<float>::quiet_NaN();
                          std::memcpy(f, &nan, 4);
                      })
                  .find("field 'viewport' is not a finite number"),
              std::string::npos);
    EXPECT_EQ(refusal(cmd::SetIndexBuffer{}, [](std::byte*) {}), "(accepted)");
}

// The GL backend's dense records (DrawOneInstance, SetUniformOffset) are in no capture: a file
// that holds one is refused by name (a SetUniformOffset would bind whatever buffer came before).
TEST(CaptureStream, RefusesTheGlBackendsOwnRecords) {
    auto refused = [](auto record) {
        cmd::CommandStream s;
        s.push(record);
        try {
            decodeCommandStream(encodeCommandStream(s));
        } catch (const CaptureError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    for (const std::string& e : {refused(cmd::DrawOneInstance{.vertexCount = 3}),
                                 refused(cmd::SetUniformOffset{.offset = 256})})
        EXPECT_NE(e.find("the GL backend's own form of a command"), std::string::npos) << e;
}
