// Building sweep cases' nodes, apart from the sweep's tests so other executables can share it.
#include "sweep.h"

namespace softtrace::test {

NodePtr build_from_json(const std::string& text, Convention convention) {
  // Nodes keep no reference to the JSON after construction, so a local document suffices.
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, true, true);
  BuildContext ctx;
  ctx.convention = convention;
  return build_field(Params(j, "", std::make_shared<const std::string>("<test>")), ctx);
}

}  // namespace softtrace::test
