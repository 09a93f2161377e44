// SerialCouplingScheme (coupling_scheme.hpp, SPEC.md §5.3) against two
// scripted servers — a real ServerSession behind a ROUTER socket on a thread,
// with a backend that records what it was sent — so that each rule of the
// scheme is seen on the wire: the order and steps of the advances, the DEM's
// force passed to the continuum unchanged, the kinematic correction that puts
// the DEM's wall on the continuum's displacement, the force-balance check,
// failures blamed on the server that sent a NaN, and export/import of the
// state continuing exactly as an uninterrupted scheme.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <thread>

#include <zmq.hpp>

#include "dfc/common/errors.hpp"
#include "dfc/coupler/participant.hpp"
#include "dfc/coupler/serial_coupling_scheme.hpp"
#include "dfc/protocol/server_session.hpp"
#include "loopback_router.hpp"

namespace dfc::coupler {
namespace {

using namespace std::chrono_literals;
namespace protocol = dfc::protocol;

constexpr std::int64_t kNodes = 3;
constexpr double kDtDem = 1e-3;
constexpr std::int64_t kDemSteps = 4;       // k
constexpr std::int64_t kContinuumSteps = 2; // m
constexpr double kDtContinuum = kDtDem * double(kDemSteps) / double(kContinuumSteps);
constexpr double kExchange = kDtDem * double(kDemSteps);  // T

enum class Fault { none, force_mismatch, nan_velocity };

/// What the scripted servers send at exchange n (0-based): fixed functions of
/// n and the node row, so that two runs of the scheme can be compared.
double dem_force(std::int64_t n, std::size_t i) { return 0.5 + double(n) - 0.25 * double(i); }
double continuum_velocity(std::int64_t n, std::size_t i) { return 0.01 * double(i + 1) * std::sin(0.7 * double(n + 1)); }
// Not the integral of the velocity: the correction has something to correct.
double continuum_displacement(std::int64_t n, std::size_t i) { return 1e-4 * double(i + 2) * std::cos(0.3 * double(n)); }

/// A scripted DEM (accepts_interface) or continuum (provides_interface) backend.
class ScriptedSide final : public protocol::SolverBackend {
 public:
  ScriptedSide(std::string role, Fault fault) : role_(std::move(role)), fault_(fault) {}

  [[nodiscard]] protocol::SolverIdentity identity() const override {
    return {"scripted_" + role_, "1.0", role_,
            {role_ == "dem" ? protocol::capability::accepts_interface : protocol::capability::provides_interface}};
  }
  nlohmann::json configure(const nlohmann::json& /*section*/) override {
    return {{"dt_suggested", role_ == "dem" ? kDtDem : kDtContinuum}, {"dt_max", nullptr}};
  }
  protocol::InterfaceMesh interface_mesh() override { return {{7, 8, 9}, {0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2}}; }
  void set_interface(const protocol::InterfaceMesh& /*mesh*/) override {}

  protocol::AdvanceResult advance(const protocol::AdvanceRequest& request) override {
    const std::int64_t n = std::int64_t(advances.size());
    advances.push_back(request);
    protocol::AdvanceResult result;
    std::array<double, 3> sum{0.0, 0.0, 0.0};
    if (role_ == "dem") {
      std::vector<double> force;
      for (std::size_t i = 0; i < std::size_t(kNodes) * 3; ++i) force.push_back(dem_force(n, i));
      for (std::size_t i = 0; i < force.size(); ++i) sum[i % 3] -= force[i];
      result.outputs.push_back(protocol::Array::from_f64(protocol::field::force, {kNodes, 3}, force));
      result.monitors = {{"interface_force_reaction", sum}};
    } else {
      const std::vector<double> force = protocol::require_f64(request.inputs, protocol::field::force, kNodes, 3);
      for (std::size_t i = 0; i < force.size(); ++i) sum[i % 3] += force[i];
      if (fault_ == Fault::force_mismatch && n == 2) sum[0] *= 1.0 + 1e-6;
      std::vector<double> velocity, displacement;
      for (std::size_t i = 0; i < std::size_t(kNodes) * 3; ++i) {
        velocity.push_back(continuum_velocity(n, i));
        displacement.push_back(continuum_displacement(n, i));
      }
      if (fault_ == Fault::nan_velocity && n == 1) velocity[4] = std::numeric_limits<double>::quiet_NaN();
      result.outputs.push_back(protocol::Array::from_f64(protocol::field::velocity, {kNodes, 3}, velocity));
      result.outputs.push_back(protocol::Array::from_f64(protocol::field::displacement, {kNodes, 3}, displacement));
      result.monitors = {{"interface_force_received", sum}};
    }
    return result;
  }
  [[nodiscard]] nlohmann::json monitors() override { return nlohmann::json::object(); }
  [[nodiscard]] std::vector<protocol::Array> snapshot(std::string& kind) override {
    kind = "grid";
    return {};
  }

  /// Every advance received: written by the server's thread before it replies, read by the test after the reply.
  std::vector<protocol::AdvanceRequest> advances;

 private:
  std::string role_;
  Fault fault_;
};

/// A ServerSession around `backend`, served on a thread until the test ends.
class ScriptedServer {
 public:
  ScriptedServer(zmq::context_t& context, protocol::SolverBackend& backend) : router_(context), session_(backend, protocol::Limits{}) {
    thread_ = std::thread([this] {
      while (!done_) {
        const auto request = router_.receive(50ms);
        if (!request) continue;
        router_.reply(*request, session_.handle(request->decoded()));
      }
    });
  }
  ~ScriptedServer() {
    done_ = true;
    thread_.join();
  }
  [[nodiscard]] std::string endpoint() const { return router_.endpoint(); }

 private:
  protocol::testing::LoopbackRouter router_;
  protocol::ServerSession session_;
  std::atomic<bool> done_{false};
  std::thread thread_;
};

/// Two scripted servers, greeted, configured and given the interface, with a scheme over them.
struct CoupledPair {
  explicit CoupledPair(Fault fault = Fault::none)
      : dem_backend("dem", Fault::none),
        continuum_backend("continuum", fault),
        dem_server(context, dem_backend),
        continuum_server(context, continuum_backend),
        dem(context, {"dem", "scripted_dem", {}, {}, dem_server.endpoint(), nlohmann::json::object(), {}}, std::filesystem::temp_directory_path(),
            5s, {10s, 120s}, stop),
        continuum(context, {"continuum", "scripted_continuum", {}, {}, continuum_server.endpoint(), nlohmann::json::object(), {}},
                  std::filesystem::temp_directory_path(), 5s, {10s, 120s}, stop) {
    for (Participant* p : {&dem, &continuum}) {
      p->hello(5s);
      (void)p->configure(5s);
    }
    dem.client().set_interface(continuum.client().get_interface(5s), 5s);
  }
  SerialCouplingScheme scheme() { return {&dem, &continuum, {kDemSteps, kContinuumSteps, kDtDem, kDtContinuum}, kNodes, 1e-9, 5s, stop}; }

  zmq::context_t context;
  ScriptedSide dem_backend, continuum_backend;
  ScriptedServer dem_server, continuum_server;
  StopRequest stop{nullptr};
  Participant dem, continuum;
};

std::vector<double> input(const protocol::AdvanceRequest& request, const char* name) {
  return protocol::require_f64(request.inputs, name, kNodes, 3);
}

// Each exchange the DEM advances first: the continuum receives, in the same
// exchange, the force the DEM has just returned, unchanged.
TEST(SerialCouplingScheme, TheDemAdvancesFirstAndTheContinuumGetsItsForceUnchanged) {
  CoupledPair pair;
  SerialCouplingScheme scheme = pair.scheme();
  for (int n = 0; n < 3; ++n) {
    const ExchangeResult r = scheme.advance();
    EXPECT_EQ(r.exchange, n);
    EXPECT_EQ(r.dem_step, kDemSteps * (n + 1));
    EXPECT_EQ(r.continuum_step, kContinuumSteps * (n + 1));
    EXPECT_DOUBLE_EQ(r.time_s, kExchange * (n + 1));
  }
  ASSERT_EQ(pair.dem_backend.advances.size(), 3u);
  ASSERT_EQ(pair.continuum_backend.advances.size(), 3u);
  for (std::size_t n = 0; n < 3; ++n) {
    const auto& d = pair.dem_backend.advances[n];
    const auto& c = pair.continuum_backend.advances[n];
    EXPECT_EQ(d.first_step, kDemSteps * std::int64_t(n));
    EXPECT_EQ(d.n_steps, kDemSteps);
    EXPECT_EQ(d.dt, kDtDem);
    EXPECT_EQ(c.first_step, kContinuumSteps * std::int64_t(n));
    EXPECT_EQ(c.n_steps, kContinuumSteps);
    EXPECT_EQ(c.dt, kDtContinuum);
    const std::vector<double> force = input(c, protocol::field::force);
    for (std::size_t i = 0; i < force.size(); ++i) EXPECT_EQ(force[i], dem_force(std::int64_t(n), i)) << "exchange " << n << " row " << i / 3;
  }
  const CouplingState state = scheme.export_state();
  EXPECT_EQ(state.exchanges_done, 3);
  EXPECT_EQ(state.unchecked_balances, 0);
  EXPECT_EQ(state.worst_balance, 0.0);  // the scripted sums are exact negatives
}

// docs/theory/coupling.md: the DEM moves its wall at the velocity it is sent
// for the whole exchange; the sent velocity v + (u_continuum − u_wall)/T puts
// the wall, at the end of exchange n + 1, where the continuum's node will be:
// u_n + T v_n. The first exchange starts from rest.
TEST(SerialCouplingScheme, TheWallFollowsTheContinuumsDisplacement) {
  CoupledPair pair;
  SerialCouplingScheme scheme = pair.scheme();
  for (int n = 0; n < 6; ++n) (void)scheme.advance();
  const auto& sent = pair.dem_backend.advances;
  for (double v : input(sent[0], protocol::field::velocity)) EXPECT_EQ(v, 0.0);
  std::vector<double> wall(std::size_t(kNodes) * 3, 0.0);
  for (std::size_t n = 0; n + 1 < sent.size(); ++n) {
    const std::vector<double> v = input(sent[n], protocol::field::velocity);
    for (std::size_t i = 0; i < wall.size(); ++i) wall[i] += kExchange * v[i];
    const std::vector<double> next = input(sent[n + 1], protocol::field::velocity);
    for (std::size_t i = 0; i < wall.size(); ++i) {
      const double wall_after = wall[i] + kExchange * next[i];
      const double target = continuum_displacement(std::int64_t(n), i) + kExchange * continuum_velocity(std::int64_t(n), i);
      // k = 4 additions of v·dt against one product: a few ulps of 1e-4 m.
      EXPECT_NEAR(wall_after, target, 1e-17) << "exchange " << n + 1 << " row " << i / 3;
    }
  }
}

TEST(SerialCouplingScheme, ABrokenForceBalanceStopsTheRunNamingTheExchange) {
  CoupledPair pair(Fault::force_mismatch);
  SerialCouplingScheme scheme = pair.scheme();
  (void)scheme.advance();
  (void)scheme.advance();
  try {
    (void)scheme.advance();
    FAIL() << "a mismatch of 1e-6 passed a tolerance of 1e-9";
  } catch (const ParticipantFailure& e) {
    EXPECT_NE(std::string(e.what()).find("interface force balance broken at exchange 2"), std::string::npos) << e.what();
  }
}

TEST(SerialCouplingScheme, ANanVelocityIsBlamedOnTheContinuum) {
  CoupledPair pair(Fault::nan_velocity);
  SerialCouplingScheme scheme = pair.scheme();
  (void)scheme.advance();
  try {
    (void)scheme.advance();
    FAIL() << "a NaN velocity was passed on";
  } catch (const ParticipantFailure& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("server continuum"), std::string::npos) << what;
    EXPECT_NE(what.find("non-finite interface velocity"), std::string::npos) << what;
    EXPECT_NE(what.find("node row 1"), std::string::npos) << what;
  }
  EXPECT_EQ(pair.dem_backend.advances.size(), 2u);  // the DEM never saw it
}

// A checkpoint's view: a new scheme that imports the exported state sends the
// servers exactly what the uninterrupted scheme sends.
TEST(SerialCouplingScheme, AnImportedStateContinuesBitForBit) {
  CoupledPair whole, split;
  CouplingState whole_state;
  {
    SerialCouplingScheme scheme = whole.scheme();
    for (int n = 0; n < 6; ++n) (void)scheme.advance();
    whole_state = scheme.export_state();
  }
  CouplingState state;
  {
    SerialCouplingScheme first = split.scheme();
    for (int n = 0; n < 3; ++n) (void)first.advance();
    state = first.export_state();
  }
  SerialCouplingScheme second = split.scheme();
  second.import_state(state);
  for (int n = 3; n < 6; ++n) EXPECT_EQ(second.advance().exchange, n);
  ASSERT_EQ(split.dem_backend.advances.size(), 6u);
  for (std::size_t n = 0; n < 6; ++n) {
    EXPECT_EQ(split.dem_backend.advances[n].first_step, whole.dem_backend.advances[n].first_step);
    EXPECT_EQ(input(split.dem_backend.advances[n], protocol::field::velocity), input(whole.dem_backend.advances[n], protocol::field::velocity))
        << "exchange " << n;
  }
  EXPECT_EQ(second.export_state().wall_displacement, whole_state.wall_displacement);
}

}  // namespace
}  // namespace dfc::coupler
