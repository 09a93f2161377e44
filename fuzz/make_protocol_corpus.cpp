// Writes the protocol fuzzer's seed corpus (fuzz/corpus/protocol/): message
// sequences in the layout of fuzz_input.hpp that walk the session through
// each state of SPEC.md §5.1 with valid messages, plus a few that each stop
// at one check of §3.1. Seeds that already reach deep states let the fuzzer
// spend its time mutating them rather than rediscovering the handshake.
//
//   make_protocol_corpus DIR     (overwrites DIR/NN_name files)
#include <cstdint>
#include <cstdio>
#include <optional>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "dfc/protocol/codec.hpp"
#include "dfc/protocol/message.hpp"
#include "fuzz_input.hpp"

namespace {

using dfc::protocol::Array;
using dfc::protocol::Message;
namespace type = dfc::protocol::type;

std::int64_t g_seq = 0;  // requests of one sequence are numbered 0, 1, 2, ... as a client numbers them

std::string bytes_of(const Array& array) { return std::string(reinterpret_cast<const char*>(array.bytes.data()), array.bytes.size()); }

/// One framed message of `type` with `body`, `step` and `arrays`.
std::string framed(std::string_view message_type, nlohmann::json body = nlohmann::json::object(), std::optional<std::int64_t> step = std::nullopt,
                   const std::vector<Array>& arrays = {}) {
  Message message;
  message.type = std::string(message_type);
  message.seq = g_seq++;
  message.step = step;
  message.body = std::move(body);
  message.arrays = arrays;
  std::vector<std::string> frames;
  for (const auto& array : arrays) frames.push_back(bytes_of(array));
  return dfc::fuzz::write_frames(dfc::protocol::encode_header(message), frames);
}

std::string hello() { return framed(type::hello, {{"client", {{"name", "fuzz"}, {"version", "1"}}}}); }
std::string configure(const nlohmann::json& section) { return framed(type::configure, {{"section_json", section.dump()}}); }
std::string advance(std::int64_t step, std::int64_t n_steps, double dt, const std::vector<Array>& arrays) {
  return framed(type::advance, {{"n_steps", n_steps}, {"dt", dt}}, step, arrays);
}
Array f64(const char* name, std::vector<std::int64_t> shape, double value) {
  std::int64_t count = 1;
  for (const auto e : shape) count *= e;
  return Array::from_f64(name, std::move(shape), std::vector<double>(std::size_t(count), value));
}

struct Seed {
  std::string name;
  std::vector<std::string> messages;
};

std::vector<Seed> seeds() {
  std::vector<Seed> out;
  const auto add = [&](std::string name, auto make) {
    g_seq = 0;
    out.push_back({std::move(name), make()});
  };
  add("hello", [] { return std::vector{hello()}; });
  add("provider_run", [] {
    return std::vector{hello(),           configure({{"side", 3}}),     framed(type::get_interface),
                       advance(0, 2, 1e-3, {f64("force", {9, 3}, 1.5)}), framed(type::query), framed(type::snapshot),
                       advance(2, 1, 1e-3, {f64("force", {9, 3}, -0.5), f64("mass", {9}, 2.0)}), framed(type::shutdown)};
  });
  add("driven_run", [] {
    const std::vector<std::int64_t> ids{7, 8, 9};
    const std::vector<std::int64_t> facets{0, 1, 2};
    const std::vector<Array> mesh{Array::from_i64("node_ids", {3}, ids),
                                  Array::from_f64("coordinates", {3, 3}, std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0}),
                                  Array::from_i64("facets", {1, 3}, facets)};
    return std::vector{hello(), configure({{"gravity_m_s2", {0, 0, -9.81}}}), framed(type::set_interface, {}, std::nullopt, mesh),
                       advance(0, 1, 5e-3, {f64("velocity", {3, 3}, 0.25)}), framed(type::query)};
  });
  add("unstable_then_stable", [] {
    return std::vector{hello(), configure({{"dt_max", 1e-3}}), advance(0, 1, 1.0, {f64("force", {4, 3}, 0.0)}),
                       advance(0, 1, 1e-4, {f64("force", {4, 3}, 1.0)})};
  });
  add("solver_failure", [] {
    return std::vector{hello(), configure({{"fail_after_steps", 1}}), advance(0, 2, 1e-3, {f64("force", {4, 3}, 0.0)}),
                       framed(type::query), framed(type::snapshot), advance(0, 1, 1e-3, {f64("force", {4, 3}, 0.0)}), framed(type::ping)};
  });
  add("out_of_order", [] {
    return std::vector{framed(type::advance, {{"n_steps", 1}, {"dt", 1e-3}}, 0), configure(nlohmann::json::object()), hello(), hello(), framed(type::get_interface),
                       framed(type::shutdown), framed(type::ping)};
  });
  add("checkpoint_unsupported", [] {
    return std::vector{hello(), configure(nlohmann::json::object()), framed(type::checkpoint, {{"path", "state.ckpt"}}), framed(type::restore, {{"path", "state.ckpt"}})};
  });
  add("bad_headers", [] {
    return std::vector<std::string>{
        "",                                                                        // no frames
        dfc::fuzz::write_frames("not json", {}),                                   // BAD_MESSAGE, no reply_to
        dfc::fuzz::write_frames(R"({"protocol":"dfc","version":"1.5","type":"hello"})", {}),  // seq missing
        dfc::fuzz::write_frames(R"({"protocol":"dfc","version":"2.0","type":"hello","seq":3})", {}),  // VERSION_MISMATCH
        dfc::fuzz::write_frames(R"({"protocol":"dfc","version":"1.5","type":"launch","seq":4})", {}),  // UNKNOWN_TYPE
        dfc::fuzz::write_frames(R"({"protocol":"dfc","version":"1.x","type":"hello","seq":5,"body":[]})", {}),
        dfc::fuzz::write_frames(R"({"protocol":"dfc","version":"1.5","type":"hello","seq":6,"step":-1,"reply_to":1.5})", {})};
  });
  add("bad_arrays", [] {
    const std::string eight(8, '\0');
    return std::vector<std::string>{
        dfc::fuzz::write_frames(R"({"protocol":"dfc","version":"1.5","type":"ping","seq":0,"arrays":[{"name":"a","dtype":"f64","shape":[2]}]})",
                                std::vector<std::string>{eight}),  // frame too short: BAD_ARRAY
        dfc::fuzz::write_frames(
            R"({"protocol":"dfc","version":"1.5","type":"ping","seq":1,"arrays":[{"name":"a","dtype":"u8","shape":[8]},{"name":"a","dtype":"i32","shape":[2]}]})",
            std::vector<std::string>{eight, eight}),  // duplicate names
        dfc::fuzz::write_frames(R"({"protocol":"dfc","version":"1.5","type":"ping","seq":2,"arrays":[{"name":"s","dtype":"f32","shape":[]}]})",
                                std::vector<std::string>{std::string(4, '\0')}),  // a scalar
        dfc::fuzz::write_frames(
            R"({"protocol":"dfc","version":"1.5","type":"ping","seq":3,"arrays":[{"name":"z","dtype":"u8","shape":[4294967296,2147483648,0]}]})",
            std::vector<std::string>{std::string()}),  // empty, with huge extents before the zero
        dfc::fuzz::write_frames(
            R"({"protocol":"dfc","version":"1.5","type":"ping","seq":4,"arrays":[{"name":"big","dtype":"f64","shape":[4294967296,4294967296]}]})",
            std::vector<std::string>{std::string()})};  // TOO_LARGE before any allocation
  });
  add("tight_limits", [] {
    std::vector<std::string> frames{std::string(100, 'x')};
    return std::vector<std::string>{
        dfc::fuzz::write_frames(R"({"protocol":"dfc","version":"1.5","type":"ping","seq":0,"arrays":[{"name":"x","dtype":"u8","shape":[100]}]})",
                                frames, true),  // one frame over max_array_bytes
        dfc::fuzz::write_frames(R"({"protocol":"dfc","version":"1.5","type":"ping","seq":1,"body":{"pad":")" + std::string(600, 'p') + "\"}}", {},
                                true)};  // header over max_header_bytes
  });
  add("bad_configure", [] {
    return std::vector<std::string>{hello(), framed(type::configure, {{"section_json", R"({"side": 2, "side": 3})"}}),
                                    framed(type::configure, {{"section_json", std::string(70, '[') + std::string(70, ']')}}),
                                    framed(type::configure, {{"section_json", R"({"side": "x\u00e9\u00e9\u00e9\u00e9\u00e9\u00e9\u00e9\u00e9\u00e9\u00e9\u00e9\u00e9\u00e9\u00e9\u00e9\u00e9\u00e9\u00e9\u00e9\u00e9"})"}}),
                                    framed(type::configure, {{"section_json", R"({"sied": 3})"}}), framed(type::configure, {{"section_json", 3}}),
                                    configure({{"side", 4}})};
  });
  add("bad_advance", [] {
    return std::vector{hello(), configure(nlohmann::json::object()), advance(1, 1, 1e-3, {f64("force", {4, 3}, 0.0)}), advance(0, 0, 1e-3, {}),
                       advance(0, 1, -1.0, {}), advance(0, 1, 1e-3, {f64("force", {4, 2}, 0.0)}),
                       advance(0, 1, 1e-3, {f64("force", {4, 3}, 0.0), f64("velocity", {4, 3}, 0.0)}), framed(type::advance, {{"dt", 1e-3}}, 0)};
  });
  // Regression seeds of what the fuzzer found (tests/protocol/fuzz_findings_test.cpp): error texts that quote
  // bytes which are not UTF-8 (a header's, and a configure value cut inside a character, in 11_bad_configure).
  add("not_utf8", [] {
    return std::vector<std::string>{dfc::fuzz::write_frames("{\"seq\": 1, \"note\": \"\xFF\xFE\"}", {}), hello()};
  });
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_protocol_corpus DIR\n";
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  std::filesystem::create_directories(dir);
  int index = 0;
  for (const auto& seed : seeds()) {
    char prefix[8];
    std::snprintf(prefix, sizeof prefix, "%02d_", ++index);
    std::ofstream out(dir / (prefix + seed.name), std::ios::binary | std::ios::trunc);
    const std::string bytes = dfc::fuzz::join_messages(seed.messages);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    if (!out) {
      std::cerr << "make_protocol_corpus: cannot write " << (dir / seed.name).string() << "\n";
      return 1;
    }
  }
  std::cout << "wrote " << index << " seeds to " << dir.string() << "\n";
  return 0;
}
