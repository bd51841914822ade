// The pipeline orders modules from their declarations and refuses what cannot run: two
// providers, a requirement nobody provides, a cycle. Errors name modules and representations
// readably.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "robot/Error.h"
#include "robot/Module.h"

namespace nao {
namespace {

struct Raw {
  int value = 0;
};
struct Filtered {
  int value = 0;
};
struct Model {
  int value = 0;
};
struct Decision {
  int value = 0;
};

class Filter : public Module<Filter, Requires<Raw>, Provides<Filtered>> {
  void update() override { out<Filtered>().value = in<Raw>().value * 2; }
};
class Modeler : public Module<Modeler, Requires<Filtered>, Provides<Model>, Cadence::Cognition> {
  void update() override { out<Model>().value = in<Filtered>().value + 1; }
};
class Decider : public Module<Decider, Requires<Model, Filtered>, Provides<Decision>, Cadence::Cognition> {
  void update() override { out<Decision>().value = in<Model>().value * 10 + in<Filtered>().value; }
};
class OtherFilter : public Module<OtherFilter, Requires<Raw>, Provides<Filtered>> {
  void update() override { out<Filtered>().value = -1; }
};
// A -> B -> C -> A through Model, Decision and Filtered.
class LoopA : public Module<LoopA, Requires<Decision>, Provides<Filtered>> {
  void update() override {}
};
class LoopB : public Module<LoopB, Requires<Filtered>, Provides<Model>> {
  void update() override {}
};
class LoopC : public Module<LoopC, Requires<Model>, Provides<Decision>> {
  void update() override {}
};

// The loop closed through Previous<>: A reads C's Decision of the last run.
class PrevLoopA : public Module<PrevLoopA, Requires<Previous<Decision>, Raw>, Provides<Filtered>> {
  void update() override { out<Filtered>().value = in<Raw>().value + in<Previous<Decision>>().value; }
};
class PrevLoopC : public Module<PrevLoopC, Requires<Model>, Provides<Decision>> {
  void update() override { out<Decision>().value = in<Model>().value * 10; }
};
// Previous<> of what nothing provides.
class PrevOrphan : public Module<PrevOrphan, Requires<Previous<Decision>>, Provides<Model>> {
  void update() override {}
};

std::string sortError(Pipeline& p) {
  try {
    p.sort();
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), "module pipeline");
    return e.what();
  }
  return "";
}

TEST(Pipeline, OrdersByDeclarationsWhateverTheOrderAdded) {
  Pipeline p;
  p.add(std::make_unique<Decider>());
  p.add(std::make_unique<Modeler>());
  p.add(std::make_unique<Filter>());
  p.inputs<Raw>();
  p.sort();
  EXPECT_EQ(p.order(), (std::vector<std::string>{"Filter", "Modeler", "Decider"}));
  Blackboard board;
  board.write<Raw>().value = 3;
  p.update(board);
  EXPECT_EQ(board.read<Filtered>().value, 6);
  EXPECT_EQ(board.read<Model>().value, 7);
  EXPECT_EQ(board.read<Decision>().value, 76);
}

TEST(Pipeline, DeclarationsAreVisibleWithReadableNames) {
  Decider d;
  EXPECT_EQ(d.name(), "Decider");
  EXPECT_EQ(d.cadence(), Cadence::Cognition);
  ASSERT_EQ(d.required().size(), 2u);
  EXPECT_EQ(d.required()[0].name, "Model");
  EXPECT_EQ(d.required()[1].name, "Filtered");
  EXPECT_EQ(d.provided()[0].name, "Decision");
  EXPECT_EQ(Filter().cadence(), Cadence::Motion);
}

TEST(Pipeline, TwoProvidersOfOneRepresentation) {
  Pipeline p;
  p.inputs<Raw>();
  p.add(std::make_unique<Filter>());
  p.add(std::make_unique<OtherFilter>());
  EXPECT_EQ(sortError(p), "module pipeline: Filtered is provided by both Filter and OtherFilter");
}

TEST(Pipeline, AnInputThatAModuleProvidesToo) {
  Pipeline p;
  p.inputs<Raw, Filtered>();
  p.add(std::make_unique<Filter>());
  EXPECT_EQ(sortError(p), "module pipeline: Filtered is an input of the pipeline and provided by Filter too");
}

TEST(Pipeline, MissingProvider) {
  Pipeline p;
  p.add(std::make_unique<Filter>());  // Raw is not declared as an input
  EXPECT_EQ(sortError(p), "module pipeline: Filter requires Raw, which no module provides and no input is");
  Pipeline q;
  q.inputs<Raw>();
  q.add(std::make_unique<Decider>());
  q.add(std::make_unique<Filter>());  // nobody provides Model
  EXPECT_EQ(sortError(q), "module pipeline: Decider requires Model, which no module provides and no input is");
}

TEST(Pipeline, CycleIsNamedWithItsPath) {
  Pipeline p;
  p.add(std::make_unique<LoopA>());
  p.add(std::make_unique<LoopB>());
  p.add(std::make_unique<LoopC>());
  EXPECT_EQ(sortError(p),
            "module pipeline: dependency cycle: LoopA requires Decision from LoopC requires Model from "
            "LoopB requires Filtered from LoopA");
  // A failed sort leaves every module in place.
  EXPECT_EQ(p.modules().size(), 3u);
  for (const auto& m : p.modules()) EXPECT_NE(m, nullptr);
}

TEST(Pipeline, InputsSatisfyRequirementsAndMissingInputsAreNamedAtRunTime) {
  Pipeline p;
  p.inputs<Raw, Filtered>();
  p.add(std::make_unique<Decider>());
  p.add(std::make_unique<Modeler>());
  p.sort();
  EXPECT_EQ(p.order(), (std::vector<std::string>{"Modeler", "Decider"}));
  Blackboard board;
  try {
    p.update(board);  // nobody wrote Filtered
    FAIL() << "no error";
  } catch (const std::logic_error& e) {
    EXPECT_STREQ(e.what(), "blackboard: nothing provides Filtered");
  }
}

TEST(Pipeline, EmptyAndIndependentModulesKeepTheirOrder) {
  Pipeline empty;
  empty.sort();
  EXPECT_TRUE(empty.order().empty());
  Pipeline p;
  p.inputs<Raw>();
  p.add(std::make_unique<Filter>());
  EXPECT_EQ(p.order(), (std::vector<std::string>{"Filter"}));
}

TEST(Pipeline, PreviousClosesALoopWithTheLastRunsValue) {
  Pipeline p;
  p.add(std::make_unique<PrevLoopC>());
  p.add(std::make_unique<LoopB>());
  p.add(std::make_unique<PrevLoopA>());
  p.inputs<Raw>();
  p.sort();  // no cycle: Previous<> adds no edge
  EXPECT_EQ(p.order(), (std::vector<std::string>{"PrevLoopA", "LoopB", "PrevLoopC"}));
  const auto required = PrevLoopA::declaredRequires();
  ASSERT_EQ(required.size(), 2u);
  EXPECT_EQ(required[0].name, "Decision");
  EXPECT_TRUE(required[0].previous);
  EXPECT_FALSE(required[1].previous);
  Blackboard board;
  board.write<Raw>().value = 1;
  // LoopB copies nothing (its update is empty), so Model stays what the test writes.
  board.write<Model>().value = 5;
  p.update(board);  // A reads the default Decision (0)
  EXPECT_EQ(board.read<Filtered>().value, 1);
  EXPECT_EQ(board.read<Decision>().value, 50);
  board.write<Model>().value = 7;
  p.update(board);  // A reads the last run's Decision (50), C then writes 70
  EXPECT_EQ(board.read<Filtered>().value, 51);
  EXPECT_EQ(board.read<Decision>().value, 70);
}

TEST(Pipeline, PreviousStillNeedsAProvider) {
  Pipeline p;
  p.add(std::make_unique<PrevOrphan>());
  EXPECT_EQ(sortError(p), "module pipeline: PrevOrphan requires Decision, which no module provides and no input is");
}

TEST(TypeName, ReadableNames) {
  EXPECT_EQ(typeName<Raw>(), "Raw");
  EXPECT_EQ(typeName<Error>(), "Error");
  EXPECT_EQ(typeName<std::string>().find("std::"), 0u);
  EXPECT_EQ(shortTypeName<Filter>(), "Filter");
  EXPECT_EQ((typeName<std::pair<Raw, Model>>()), "std::pair<Raw, Model>");
}

}  // namespace
}  // namespace nao
