#pragma once
// Modules of the robot program and the pipeline that orders them (docs/architecture.md).
//
// A module declares what it reads and what it writes in its type:
//
//   class FallDetector : public Module<FallDetector, Requires<SensorFrame>, Provides<FallState>> {
//     void update() override { out<FallState>() = detector_.update(in<SensorFrame>()); }
//   };
//
// in<T>() returns a const reference and compiles only for a T in Requires<>; out<T>() returns
// a mutable reference and compiles only for a T in Provides<>. The board itself is out of
// reach, so a module cannot read or write anything it did not declare. The Pipeline orders the
// modules from these declarations.
//
// Previous<T> in Requires<> (B-Human's USES) reads T as its provider left it in the last run of
// this cadence (default-constructed before the first): in<Previous<T>>() returns a const T&. It
// adds no ordering edge, so two modules can each read the other's output, one of them a run
// late (a behaviour that asks a calibrator and reads its status).
//
// Debug: a module tests debugging(kChannel) and writes debug(kChannel, [&] { return json; })
// on a channel declared in its .cpp (NAO_DEBUG_CHANNEL, robot/Debug.h); the payload is built
// only while the channel is subscribed.
#include <memory>
#include <string>
#include <tuple>
#include <type_traits>
#include <typeindex>
#include <utility>
#include <vector>

#include "robot/Blackboard.h"
#include "robot/Debug.h"
#include "robot/TypeName.h"

namespace nao {

template <class... T>
struct Requires {};
template <class T>
struct Previous {};
template <class... T>
struct Provides {};

// Motion runs every LoLA cycle (12 ms); cognition once per camera image.
enum class Cadence { Motion, Cognition };
inline const char* cadenceName(Cadence c) { return c == Cadence::Motion ? "motion" : "cognition"; }

// A representation's type with its readable name (for errors, tables and config/modules.json).
struct RepresentationType {
  std::type_index type;
  std::string name;
  bool previous = false;  // required as Previous<T>: the last run's value, no ordering edge
  template <class T>
  static RepresentationType of() {
    return {std::type_index(typeid(T)), typeName<T>()};
  }
  bool operator==(const RepresentationType& o) const { return type == o.type; }
};

// What the pipeline sees of a module.
class ModuleBase {
 public:
  virtual ~ModuleBase() = default;
  virtual const std::string& name() const = 0;
  virtual Cadence cadence() const = 0;
  virtual std::vector<RepresentationType> required() const = 0;
  virtual std::vector<RepresentationType> provided() const = 0;
  // Looks up the declared representations on this board (creating the provided ones) and
  // runs update(). A required one missing from the board throws, naming it.
  virtual void execute(Blackboard& board) = 0;

  // The program's debug channels (not owned; null: none), handed over by the pipeline or
  // createModule.
  void attachDebug(DebugChannels* debug) { debug_ = debug ? debug : &DebugChannels::none(); }
  DebugChannels& debugChannels() const { return *debug_; }

 protected:
  bool debugging(const DebugChannel& channel) const { return debug_->on(channel); }
  // One line on `channel` if it is subscribed; payload() (returning nlohmann::json) runs only then.
  template <class F>
  void debug(const DebugChannel& channel, F&& payload) {
    debug_->emit(channel, std::forward<F>(payload));
  }

 private:
  DebugChannels* debug_ = &DebugChannels::none();
};

namespace detail {
// A requirement's representation: T for T and for Previous<T>.
template <class R>
struct Stored {
  using type = R;
  static constexpr bool previous = false;
};
template <class T>
struct Stored<Previous<T>> {
  using type = T;
  static constexpr bool previous = true;
};
template <class R>
using StoredT = typename Stored<R>::type;
template <class R>
RepresentationType requirement() {
  RepresentationType t = RepresentationType::of<StoredT<R>>();
  t.previous = Stored<R>::previous;
  return t;
}
template <class T, class... L>
inline constexpr bool contains = (std::is_same_v<T, L> || ...);
template <class... L>
struct distinct : std::true_type {};
template <class H, class... L>
struct distinct<H, L...> : std::bool_constant<!contains<H, L...> && distinct<L...>::value> {};
}  // namespace detail

template <class Derived, class Req, class Prov, Cadence C = Cadence::Motion>
class Module;

template <class Derived, class... R, class... P, Cadence C>
class Module<Derived, Requires<R...>, Provides<P...>, C> : public ModuleBase {
  static_assert(sizeof...(P) > 0, "a module provides at least one representation");
  static_assert(detail::distinct<detail::StoredT<R>...>::value, "a representation is listed twice in Requires<>");
  static_assert(detail::distinct<P...>::value, "a representation is listed twice in Provides<>");
  static_assert(!(detail::contains<detail::StoredT<R>, P...> || ...),
                "a module cannot require what it provides (keep the state in the module instead)");

 public:
  static constexpr Cadence kCadence = C;
  static std::vector<RepresentationType> declaredRequires() { return {detail::requirement<R>()...}; }
  static std::vector<RepresentationType> declaredProvides() { return {RepresentationType::of<P>()...}; }

  const std::string& name() const override { return shortTypeName<Derived>(); }
  Cadence cadence() const override { return C; }
  std::vector<RepresentationType> required() const override { return declaredRequires(); }
  std::vector<RepresentationType> provided() const override { return declaredProvides(); }
  void execute(Blackboard& board) final {
    in_ = std::tuple<const detail::StoredT<R>*...>(input<R>(board)...);
    out_ = std::tuple<P*...>(&board.write<P>()...);
    update();
  }

 protected:
  // Computes the provisions from the requirements, once per run of the module's cadence.
  virtual void update() = 0;

  template <class T>
  const detail::StoredT<T>& in() const {
    static_assert(detail::contains<T, R...>, "in<T>(): T is not in this module's Requires<>");
    return *std::get<const detail::StoredT<T>*>(in_);
  }
  template <class T>
  T& out() {
    static_assert(detail::contains<T, P...>, "out<T>(): T is not in this module's Provides<>");
    return *std::get<T*>(out_);
  }

 private:
  // A requirement must be on the board; a Previous<T> is created there before its provider's first run.
  template <class Q>
  static const detail::StoredT<Q>* input(Blackboard& board) {
    if constexpr (detail::Stored<Q>::previous) return &board.write<detail::StoredT<Q>>();
    else return &board.read<Q>();
  }
  std::tuple<const detail::StoredT<R>*...> in_{};
  std::tuple<P*...> out_{};
};

// Runs modules in dependency order. Representations written from outside the modules (the
// backend's sensor data and images, the configuration, requests a scenario sets) are declared
// as inputs.
class Pipeline {
 public:
  void add(std::unique_ptr<ModuleBase> module) {
    if (debug_) module->attachDebug(debug_);
    modules_.push_back(std::move(module));
    sorted_ = false;
  }
  // Hands `debug` (not owned) to every module, now and when added, and writes the `timing`
  // channel under `name` ("motion", "cognition", "vision_top"). Null: none.
  void setDebug(DebugChannels* debug, std::string name);
  template <class... T>
  void inputs() {
    (input(RepresentationType::of<T>()), ...);
  }
  void input(RepresentationType type) {
    inputs_.push_back(std::move(type));
    sorted_ = false;
  }
  // Orders the modules so that every requirement is provided before it is read. Throws
  // nao::Error (where: "module pipeline") naming the modules and the representation for a
  // representation with two providers (or an input that a module provides too), a requirement
  // that nothing provides, and a dependency cycle (with its path).
  void sort();
  void update(Blackboard& blackboard);
  std::vector<std::string> order() const;
  const std::vector<std::unique_ptr<ModuleBase>>& modules() const { return modules_; }
  // Whether `timing` lines are wanted, and one line for a run that took ms[i] for modules()[i]
  // (for a caller that runs the modules itself, as CameraPipeline does).
  bool timing() const;
  void writeTiming(const std::vector<double>& ms);
  // One `timing` line with every module's runs, mean and maximum ms since subscribed; modules
  // that never ran are listed with 0 runs (the owner writes it at the end, e.g. ~RobotProgram).
  void writeTimingSummary() const;

 private:
  std::vector<std::unique_ptr<ModuleBase>> modules_;
  std::vector<RepresentationType> inputs_;
  bool sorted_ = false;
  DebugChannels* debug_ = nullptr;
  std::string name_;
  long timedRuns_ = 0;
  std::vector<double> sumMs_, maxMs_;  // per module, in order, over the timed runs
};

}  // namespace nao
