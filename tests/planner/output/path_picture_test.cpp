// The picture is well-formed SVG whatever the scene's name holds: markup in it is shown
// as text, never run.

#include "gplanner/planner/output/path_picture.h"

#include <gtest/gtest.h>
#include <tinyxml2.h>

#include <fstream>
#include <sstream>
#include <string>

#include "gplanner/planner/scene/scene.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

TEST(PathPicture, MarkupInTheSceneNameIsEscaped) {
  Scene scene = load_scene(testing::project_root() + "/scenes/pr2_base_arm.yaml");
  scene.name = "<script>alert(\"x\")</script> & <b a='1'>";
  const std::vector<float> path = testing::sample_configurations(scene, 2, 5);
  testing::ScratchFolder scratch;
  const std::string file = scratch.path() + "/path.svg";
  write_path_picture(file, scene, path);
  const std::string svg = testing::read_file(file);
  EXPECT_EQ(svg.find("<script"), std::string::npos) << "no raw <script> element";
  EXPECT_NE(svg.find("&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt; &amp; &lt;b"),
            std::string::npos);

  tinyxml2::XMLDocument document;
  ASSERT_EQ(document.Parse(svg.data(), svg.size()), tinyxml2::XML_SUCCESS) << document.ErrorStr();
  const tinyxml2::XMLElement* title = document.RootElement()->FirstChildElement("text");
  ASSERT_NE(title, nullptr);
  ASSERT_NE(title->GetText(), nullptr);
  EXPECT_EQ(std::string(title->GetText()).rfind(scene.name + ": 2 waypoints", 0), 0u)
      << "the name read back as written: " << title->GetText();
  EXPECT_EQ(title->FirstChildElement(), nullptr) << "no element inside the title";
}

}  // namespace
}  // namespace gplanner
