// The viewer's re-render decision against the option table: changing any user option (every
// value of every choice, and a new number for each numeric option) makes the frame outdated. The
// hand-written comparison this replaces missed stencil_layers, position, position_space and
// primitive_id, so changing them in the panel did not re-render.
#include <gtest/gtest.h>

#include "views/ui/viewer_model.h"

namespace gb {

TEST(ViewerModel, ChangingAnyOptionOfTheTableRendersAgain) {
  const RenderOptions rendered;
  int checked = 0;
  for (const OptionInfo& info : optionTable()) {
    std::vector<std::string> values = info.choices;
    if (info.kind == OptionKind::Integer) values = {"64"};  // valid for every integer option (shadow map >= 16)
    if (info.kind == OptionKind::Real) values = {"0.3125"};
    if (info.kind == OptionKind::Text) values = {"37x23"};  // size
    for (const std::string& v : values) {
      RenderOptions wanted = rendered;
      std::string error;
      ASSERT_TRUE(setOption(wanted, info.name, v, error)) << info.name << "=" << v << ": " << error;
      if (getOption(wanted, info.name) == getOption(rendered, info.name)) continue;  // the default value
      EXPECT_TRUE(frameOutdated(rendered, wanted)) << info.name << "=" << v;
      ++checked;
    }
  }
  for (const char* name : {"stencil_layers", "position", "position_space", "primitive_id"}) {
    const OptionInfo* info = findOption(name);
    ASSERT_NE(info, nullptr) << name;
  }
  EXPECT_GE(checked, 30);  // every non-default choice and one value per numeric option
  EXPECT_FALSE(frameOutdated(rendered, RenderOptions{}));
  RenderOptions coverage = rendered;
  coverage.coverage = !coverage.coverage;  // not a user option, but it changes the targets
  EXPECT_TRUE(frameOutdated(rendered, coverage));
}

}  // namespace gb
