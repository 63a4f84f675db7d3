#include "gplanner/planner/scene/urdf_loader.h"

#include <console_bridge/console.h>
#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>
#include <locale>
#include <mutex>
#include <set>
#include <sstream>

#include "gplanner/planner/scene/input_file.h"
#include "gplanner/planner/scene/input_limits.h"
#include "gplanner/planner/scene/mesh_components.h"
#include "gplanner/planner/scene/mesh_loader.h"

namespace gplanner {
namespace {

namespace fs = std::filesystem;

// urdfdom reports why a file or an element fails through console_bridge; capture the
// errors so that our messages can say them. console_bridge's handler is process-global.
class CapturingOutputHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) errors.push_back(text);
  }
  std::vector<std::string> errors;
};

std::mutex urdf_parser_mutex;

// Line numbers of named elements (<link name=...>, <joint name=...>), for messages.
std::map<std::string, int> element_lines(const tinyxml2::XMLDocument& doc, const char* tag) {
  std::map<std::string, int> lines;
  const tinyxml2::XMLElement* root = doc.RootElement();
  for (const tinyxml2::XMLElement* e = root ? root->FirstChildElement(tag) : nullptr; e;
       e = e->NextSiblingElement(tag)) {
    if (const char* name = e->Attribute("name")) lines.emplace(name, e->GetLineNum());
  }
  return lines;
}

Eigen::Isometry3d to_isometry(const urdf::Pose& pose) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  Eigen::Quaterniond q(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z);
  X.linear() = q.normalized().toRotationMatrix();
  return X;
}

JointType to_joint_type(int urdf_type) {
  switch (urdf_type) {
    case urdf::Joint::REVOLUTE:
      return JointType::kRevolute;
    case urdf::Joint::CONTINUOUS:
      return JointType::kContinuous;
    case urdf::Joint::PRISMATIC:
      return JointType::kPrismatic;
    case urdf::Joint::FLOATING:
      return JointType::kFloating;
    case urdf::Joint::PLANAR:
      return JointType::kPlanar;
    default:
      return JointType::kFixed;
  }
}

// The triangles of one collision shape that check_collision has read from the XML
// already, so that its sizes and scale are known to be positive (non-zero) and finite.
TriangleMesh collision_geometry(const urdf::Geometry& geometry, const std::string& urdf_folder,
                                const PackageMap& packages, const SourceLocation& where,
                                std::vector<std::string>* notices,
                                std::vector<std::string>* mesh_files) {
  switch (geometry.type) {
    case urdf::Geometry::BOX: {
      const auto& box = static_cast<const urdf::Box&>(geometry);
      return make_box(Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z));
    }
    case urdf::Geometry::SPHERE:
      return make_sphere(static_cast<const urdf::Sphere&>(geometry).radius);
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
      return make_cylinder(cylinder.radius, cylinder.length);
    }
    case urdf::Geometry::MESH: {
      const auto& mesh = static_cast<const urdf::Mesh&>(geometry);
      const std::string path = resolve_resource(mesh.filename, urdf_folder, packages, where);
      return load_mesh(path, Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z), where,
                       notices, mesh_files);
    }
  }
  throw InputError(where, "unsupported collision geometry");
}

// Reads the URDF or SRDF at `path` (within `kind`'s size bound) into `doc` and returns its
// text; XML that is not well-formed is an InputError at the line tinyxml2 names.
std::string parse_xml_file(const std::string& path, const InputFileKind& kind,
                           const SourceLocation& referenced_from, tinyxml2::XMLDocument* doc) {
  std::string xml = read_input_file(path, kind, referenced_from);
  if (doc->Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS) {
    throw InputError({path, doc->ErrorLineNum(), "xml"},
                     std::string("not well-formed XML: ") + doc->ErrorName() + "; fix the file");
  }
  return xml;
}

}  // namespace

std::string resolve_resource(const std::string& uri, const std::string& base_folder,
                             const PackageMap& packages, const SourceLocation& where) {
  const std::string package_prefix = "package://";
  const std::string file_prefix = "file://";
  if (uri.rfind(package_prefix, 0) == 0) {
    const std::string rest = uri.substr(package_prefix.size());
    const std::size_t slash = rest.find('/');
    const std::string package = rest.substr(0, slash);
    if (package.empty() || slash == std::string::npos) {
      throw InputError(where, "malformed URI '" + uri +
                                  "'; write package://PACKAGE/path (two slashes, then a "
                                  "package name)");
    }
    const auto it = packages.find(package);
    if (it == packages.end()) {
      throw InputError(where, "unknown package '" + package + "' in '" + uri +
                                  "'; map it to a folder in the scene's packages: section");
    }
    return (fs::path(it->second) / rest.substr(slash + 1)).lexically_normal().string();
  }
  if (uri.rfind(file_prefix, 0) == 0) return uri.substr(file_prefix.size());
  if (uri.find("://") != std::string::npos) {
    throw InputError(where, "unsupported URI scheme in '" + uri + "'; use package:// or a path");
  }
  return (fs::path(base_folder) / uri).lexically_normal().string();
}

namespace {

// The kinematic tree's structure, checked on the XML before urdfdom reads it: urdfdom
// gives no line numbers for these errors, and on some broken trees (cycles) leaks its
// links.
// Every number a link or joint gives (origins, axes, limits, mimics, inertia, shapes)
// read before urdfdom does, so that a NaN, an infinity or a word is reported with the
// joint or link, the element and its line (urdfdom names none of them).
void check_numbers(const tinyxml2::XMLDocument& doc, const std::string& path) {
  static const std::map<std::string, std::vector<const char*>> kNumbers = {
      {"origin", {"xyz", "rpy"}},
      {"axis", {"xyz"}},
      {"limit", {"lower", "upper", "effort", "velocity"}},
      {"safety_controller", {"soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"}},
      {"dynamics", {"damping", "friction"}},
      {"mimic", {"multiplier", "offset"}},
      {"mass", {"value"}},
      {"inertia", {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}},
      {"box", {"size"}},
      {"cylinder", {"radius", "length"}},
      {"sphere", {"radius"}},
      {"mesh", {"scale"}},
      {"calibration", {"rising", "falling"}}};
  const tinyxml2::XMLElement* robot = doc.RootElement();
  if (robot == nullptr) return;
  for (const char* owner_tag : {"joint", "link"}) {
    for (const tinyxml2::XMLElement* owner = robot->FirstChildElement(owner_tag); owner;
         owner = owner->NextSiblingElement(owner_tag)) {
      const char* owner_name = owner->Attribute("name");
      const std::string owner_key =
          std::string(owner_tag) + " '" + (owner_name ? owner_name : "") + "'";
      std::vector<const tinyxml2::XMLElement*> stack{owner};
      while (!stack.empty()) {
        const tinyxml2::XMLElement* element = stack.back();
        stack.pop_back();
        for (const tinyxml2::XMLElement* child = element->FirstChildElement(); child;
             child = child->NextSiblingElement()) {
          stack.push_back(child);
        }
        const auto numbers = kNumbers.find(element->Name());
        if (numbers == kNumbers.end()) continue;
        for (const char* attribute : numbers->second) {
          const char* text = element->Attribute(attribute);
          if (text == nullptr) continue;
          std::istringstream words(text);
          words.imbue(std::locale::classic());
          std::string word;
          while (words >> word) {
            char* end = nullptr;
            const double value = std::strtod(word.c_str(), &end);
            if (*end == '\0' && std::isfinite(value)) continue;
            throw InputError({path, element->GetLineNum(),
                              owner_key + " <" + element->Name() + " " + attribute + ">"},
                             "'" + word + "' is not a finite number; give a number");
          }
        }
      }
    }
  }
}

void check_tree(const tinyxml2::XMLDocument& doc, const std::string& path) {
  const tinyxml2::XMLElement* robot = doc.FirstChildElement("robot");
  if (robot == nullptr) throw InputError({path, 1, "robot"}, "no <robot> element; not a URDF");
  std::map<std::string, int> links;  // name -> line
  for (const tinyxml2::XMLElement* link = robot->FirstChildElement("link"); link;
       link = link->NextSiblingElement("link")) {
    const char* name = link->Attribute("name");
    if (name == nullptr || *name == '\0')
      throw InputError({path, link->GetLineNum(), "link"}, "a link without a name; name it");
    if (!links.emplace(name, link->GetLineNum()).second) {
      throw InputError({path, link->GetLineNum(), std::string("link '") + name + "'"},
                       "defined twice; give each link its own name");
    }
  }
  if (links.empty()) throw InputError({path, robot->GetLineNum(), "robot"}, "no links; add one");
  if (links.size() > kMaxRobotLinks) {
    throw InputError({path, robot->GetLineNum(), "robot"},
                     "has " + std::to_string(links.size()) + " links, more than the " +
                         std::to_string(kMaxRobotLinks) +
                         " a robot may have; merge fixed links or plan a smaller model");
  }
  std::map<std::string, std::string> parent_of;  // child link -> parent link
  for (const tinyxml2::XMLElement* joint = robot->FirstChildElement("joint"); joint;
       joint = joint->NextSiblingElement("joint")) {
    const char* name = joint->Attribute("name");
    const std::string key = std::string("joint '") + (name ? name : "") + "'";
    const int line = joint->GetLineNum();
    std::string ends[2];
    const char* tags[2] = {"parent", "child"};
    for (int k = 0; k < 2; ++k) {
      const tinyxml2::XMLElement* e = joint->FirstChildElement(tags[k]);
      const char* link = e ? e->Attribute("link") : nullptr;
      if (link == nullptr) {
        throw InputError({path, line, key}, std::string("no <") + tags[k] +
                                                " link=...>; name the " + tags[k] + " link");
      }
      if (!links.count(link)) {
        throw InputError({path, line, key}, std::string(tags[k]) + " link '" + link +
                                                "' is not defined; define it or fix the name");
      }
      ends[k] = link;
    }
    if (ends[0] == ends[1])
      throw InputError({path, line, key}, "joins link '" + ends[0] + "' to itself");
    if (!parent_of.emplace(ends[1], ends[0]).second) {
      throw InputError({path, line, key}, "link '" + ends[1] +
                                              "' is already the child of another joint; a URDF "
                                              "is a tree, each link with one parent joint");
    }
  }
  std::vector<std::string> roots;
  for (const auto& [name, line] : links)
    if (!parent_of.count(name)) roots.push_back(name);
  if (roots.size() > 1) {
    throw InputError({path, robot->GetLineNum(), "robot"},
                     "several root links ('" + roots[0] + "', '" + roots[1] +
                         "'); add joints so that every link hangs from one root");
  }
  // With one parent per link, a link whose ancestors never reach the root lies on a
  // cycle. Each link is walked up once: a walk stops at a link known to reach the root.
  enum Walk : char { kUnknown, kOnThisWalk, kReachesRoot };
  std::map<std::string, Walk> walked;
  for (const auto& [name, line] : links) {
    std::vector<std::string> walk;
    std::string at = name;
    while (walked[at] == kUnknown) {
      walked[at] = kOnThisWalk;
      walk.push_back(at);
      const auto parent = parent_of.find(at);
      if (parent == parent_of.end()) break;  // the root
      at = parent->second;
    }
    if (walked[at] == kOnThisWalk && parent_of.count(at)) {
      throw InputError({path, links.at(at), "link '" + at + "'"},
                       "lies on a cycle of joints; a URDF is a tree: remove a joint of the cycle");
    }
    for (const std::string& link : walk) walked[link] = kReachesRoot;
  }
}

// Reads `text` as `count` finite numbers, each whitespace-separated token whole in the
// classic locale, as urdfdom reads numbers (it refuses nan and inf too).
bool read_numbers(const char* text, int count, double* values) {
  if (text == nullptr) return false;
  std::istringstream tokens(text);
  std::string token;
  int read = 0;
  while (tokens >> token) {
    if (read == count) return false;
    std::istringstream in(token);
    in.imbue(std::locale::classic());
    double value = 0;
    in >> value;
    if (in.fail() || !in.eof() || !std::isfinite(value)) return false;
    values[read++] = value;
  }
  return read == count;
}

// Throws the error for attribute `name` of `element`, missing or not what `expected`
// says, with `fix`.
[[noreturn]] void bad_attribute(const SourceLocation& where, const tinyxml2::XMLElement& element,
                                const char* name, const std::string& expected,
                                const std::string& fix) {
  const std::string tag = std::string("<") + element.Name() + "> ";
  const char* value = element.Attribute(name);
  throw InputError(where, tag +
                              (value ? std::string(name) + "=\"" + value + "\" is not "
                                     : std::string("has no ") + name + " attribute, expected ") +
                              expected + "; " + fix);
}

void check_origin(const tinyxml2::XMLElement& origin, const SourceLocation& where) {
  double values[3];
  if (origin.Attribute("xyz") && !read_numbers(origin.Attribute("xyz"), 3, values)) {
    bad_attribute(where, origin, "xyz", "three finite numbers",
                  "write the position in metres, such as xyz=\"0 0 0.1\"");
  }
  if (origin.Attribute("rpy") && !read_numbers(origin.Attribute("rpy"), 3, values)) {
    bad_attribute(where, origin, "rpy", "three finite numbers",
                  "write roll, pitch and yaw in radians, such as rpy=\"0 0 1.5708\"");
  }
}

// The shape inside a collision's <geometry>.
void check_shape(const tinyxml2::XMLElement& shape, const SourceLocation& where) {
  const std::string tag = shape.Name();
  double values[3];
  auto positive = [&](const char* name, int count) {
    if (!read_numbers(shape.Attribute(name), count, values)) return false;
    for (int k = 0; k < count; ++k)
      if (values[k] <= 0) return false;
    return true;
  };
  if (tag == "box") {
    if (!positive("size", 3)) {
      bad_attribute(where, shape, "size", "three positive finite numbers",
                    "give the side lengths in metres, such as size=\"0.1 0.2 0.3\"");
    }
  } else if (tag == "sphere") {
    if (!positive("radius", 1)) {
      bad_attribute(where, shape, "radius", "a positive finite number",
                    "give the radius in metres, such as radius=\"0.05\"");
    }
  } else if (tag == "cylinder") {
    for (const char* name : {"radius", "length"}) {
      if (!positive(name, 1)) {
        bad_attribute(where, shape, name, "a positive finite number",
                      std::string("give the ") + name + " in metres, such as " + name + "=\"0.1\"");
      }
    }
  } else if (tag == "mesh") {
    const char* filename = shape.Attribute("filename");
    if (filename == nullptr || *filename == '\0') {
      throw InputError(where,
                       "<mesh> has no filename; name the mesh file, such as "
                       "filename=\"package://PACKAGE/meshes/part.stl\"");
    }
    if (shape.Attribute("scale") && (!read_numbers(shape.Attribute("scale"), 3, values) ||
                                     values[0] == 0 || values[1] == 0 || values[2] == 0)) {
      bad_attribute(where, shape, "scale", "three finite non-zero numbers",
                    "give one factor per axis, such as scale=\"1 1 1\"");
    }
  } else {
    throw InputError(where, "<" + tag +
                                "> is not a shape a URDF collision can hold; use <box>, "
                                "<cylinder>, <sphere> or <mesh>");
  }
}

// One <collision> of link `link`, checked as strictly as the loader uses it.
void check_collision(const tinyxml2::XMLElement& collision, const std::string& path,
                     const std::string& link, std::vector<std::string>* notices) {
  const std::string key = "link '" + link + "' collision";
  for (const tinyxml2::XMLElement* e = collision.FirstChildElement(); e;
       e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag != "origin" && tag != "geometry" && notices) {
      notices->push_back(path + ":" + std::to_string(e->GetLineNum()) + ": " + key + ": <" + tag +
                         "> is not part of a URDF collision; skipped");
    }
  }
  if (const tinyxml2::XMLElement* origin = collision.FirstChildElement("origin")) {
    check_origin(*origin, {path, origin->GetLineNum(), key});
  }
  const tinyxml2::XMLElement* geometry = collision.FirstChildElement("geometry");
  if (geometry == nullptr) {
    throw InputError({path, collision.GetLineNum(), key},
                     "no <geometry>; give it a <box>, <cylinder>, <sphere> or <mesh>, or remove "
                     "the <collision>");
  }
  const tinyxml2::XMLElement* shape = geometry->FirstChildElement();
  if (shape == nullptr) {
    throw InputError({path, geometry->GetLineNum(), key},
                     "<geometry> is empty; give it one <box>, <cylinder>, <sphere> or <mesh>");
  }
  if (const tinyxml2::XMLElement* second = shape->NextSiblingElement()) {
    throw InputError({path, second->GetLineNum(), key},
                     "<geometry> holds more than one shape, and urdfdom reads only the first; "
                     "give each shape a <collision> of its own");
  }
  check_shape(*shape, {path, shape->GetLineNum(), key});
}

// A <link> element and its <collision> elements, in file order.
struct LinkElements {
  const tinyxml2::XMLElement* link = nullptr;
  std::vector<const tinyxml2::XMLElement*> collisions;
};

// The <collision> elements of each link, in file order, each checked: urdfdom drops
// every collision of a link when it cannot read one of them (a NaN or a typo in an
// origin, a scale of two numbers, an unknown shape), logging the error and going on.
// Children of a link or a collision that a URDF does not define are skipped with a
// notice: a misspelt <collision> is geometry lost.
std::map<std::string, LinkElements> check_collisions(const tinyxml2::XMLDocument& doc,
                                                     const std::string& path,
                                                     std::vector<std::string>* notices) {
  std::map<std::string, LinkElements> links;
  const tinyxml2::XMLElement* robot = doc.FirstChildElement("robot");
  for (const tinyxml2::XMLElement* link = robot->FirstChildElement("link"); link;
       link = link->NextSiblingElement("link")) {
    const std::string name = link->Attribute("name");
    LinkElements& elements = links[name];
    elements.link = link;
    for (const tinyxml2::XMLElement* e = link->FirstChildElement(); e;
         e = e->NextSiblingElement()) {
      const std::string tag = e->Name();
      if (tag == "collision") {
        check_collision(*e, path, name, notices);
        elements.collisions.push_back(e);
      } else if (tag != "visual" && tag != "inertial" && notices) {
        notices->push_back(path + ":" + std::to_string(e->GetLineNum()) + ": link '" + name +
                           "': <" + tag + "> is not part of a URDF link; skipped");
      }
    }
  }
  return links;
}

// When urdfdom read fewer collisions of a link than the file holds (it drops them all
// when it cannot read a <visual> or <inertial> of the link either), the error naming
// the element it names, or the link.
[[noreturn]] void collisions_dropped(const tinyxml2::XMLElement& link, const std::string& path,
                                     const std::vector<std::string>& urdfdom_errors) {
  const std::string name = link.Attribute("name");
  // urdfdom logs why ("Unable to parse component [abc] ..."), then "Could not parse
  // visual element for Link [NAME]".
  std::string what = "this link", why;
  const tinyxml2::XMLElement* culprit = &link;
  for (std::size_t k = 0; k < urdfdom_errors.size(); ++k) {
    if (urdfdom_errors[k].find("Link [" + name + "]") == std::string::npos) continue;
    why = k > 0 ? urdfdom_errors[k - 1] : urdfdom_errors[k];
    for (const char* tag : {"inertial", "visual", "collision"}) {
      const tinyxml2::XMLElement* e = link.FirstChildElement(tag);
      if (e &&
          urdfdom_errors[k].find(std::string("parse ") + tag + " element") != std::string::npos) {
        what = std::string("a <") + tag + ">";
        culprit = e;
      }
    }
    break;
  }
  throw InputError({path, culprit->GetLineNum(), "link '" + name + "'"},
                   "urdfdom cannot read " + what + (why.empty() ? "" : " (" + why + ")") +
                       " and so drops every collision of the link; fix it");
}

// A mimic joint follows multiplier * leader + offset. Where, over the leader's whole
// range, that leaves the follower's own limits, MoveIt loads the robot and the follower
// follows the rule beyond them (its limits bound the leader's motion only through the
// rule): so do we, with a notice (a continuous follower has no limits).
void notice_mimic_range(const Joint& follower, const Joint& leader, const SourceLocation& where,
                        std::vector<std::string>* notices) {
  const double a = follower.mimic_multiplier * leader.lower + follower.mimic_offset;
  const double b = follower.mimic_multiplier * leader.upper + follower.mimic_offset;
  const double low = std::min(a, b), high = std::max(a, b);
  if (!std::isfinite(low) || !std::isfinite(high)) {
    throw InputError(where, "multiplier and offset drive it beyond any finite value as '" +
                                leader.name + "' moves within its limits; change them");
  }
  // Limits of a single point (lower == upper, often 0 0) are a placeholder some robots
  // give mimic joints (Talos's grippers): the follower is then bounded by its leader alone.
  if (follower.type == JointType::kContinuous || !(follower.upper > follower.lower)) return;
  const double slack = 1e-9 * std::max(1.0, follower.upper - follower.lower);
  if (low >= follower.lower - slack && high <= follower.upper + slack) return;
  if (notices == nullptr) return;
  std::ostringstream problem;
  problem << where.file << ":" << where.line << ": " << where.key << ": multiplier "
          << follower.mimic_multiplier << " and offset " << follower.mimic_offset
          << " drive it over [" << low << ", " << high << "] as '" << leader.name
          << "' moves over [" << leader.lower << ", " << leader.upper
          << "], beyond its own limits [" << follower.lower << ", " << follower.upper
          << "]; it follows the mimic rule there, as in MoveIt";
  notices->push_back(problem.str());
}

}  // namespace

RobotModel load_urdf(const std::string& urdf_path, const PackageMap& packages,
                     const SourceLocation& referenced_from, std::vector<std::string>* notices) {
  tinyxml2::XMLDocument doc;
  const std::string xml = parse_xml_file(urdf_path, kUrdfFile, referenced_from, &doc);
  check_tree(doc, urdf_path);
  const std::map<std::string, LinkElements> link_elements =
      check_collisions(doc, urdf_path, notices);
  check_numbers(doc, urdf_path);
  const std::map<std::string, int> joint_lines = element_lines(doc, "joint");

  urdf::ModelInterfaceSharedPtr model;
  std::vector<std::string> urdfdom_errors;
  {
    const std::lock_guard<std::mutex> lock(urdf_parser_mutex);
    CapturingOutputHandler handler;
    console_bridge::useOutputHandler(&handler);
    model = urdf::parseURDF(xml);
    console_bridge::restorePreviousOutputHandler();
    urdfdom_errors = std::move(handler.errors);
  }
  if (!model) {
    throw InputError({urdf_path, 0, "robot"},
                     "URDF does not parse" +
                         (urdfdom_errors.empty() ? "" : ": " + urdfdom_errors.front()) +
                         "; fix the file");
  }
  auto line_of = [](const std::map<std::string, int>& lines, const std::string& name) {
    const auto it = lines.find(name);
    return it == lines.end() ? 0 : it->second;
  };

  RobotModel robot;
  robot.name = model->getName();
  robot.source_file = urdf_path;
  const std::string urdf_folder = fs::path(urdf_path).parent_path().string();

  // Breadth-first from the root: parents get lower indices than their children.
  std::deque<urdf::LinkConstSharedPtr> queue{model->getRoot()};
  std::map<std::string, int> link_index;
  while (!queue.empty()) {
    const urdf::LinkConstSharedPtr link = queue.front();
    queue.pop_front();
    const int index = static_cast<int>(robot.links.size());
    link_index[link->name] = index;
    Link out;
    out.name = link->name;
    // urdfdom keeps a link's collisions in file order, so the i-th is the i-th element.
    const auto found = link_elements.find(link->name);
    if (found == link_elements.end()) {
      throw InputError({urdf_path, 0, "link '" + link->name + "'"},
                       "urdfdom reads a link name that the file does not hold as written (an "
                       "XML entity in it?); write link names in plain characters");
    }
    const LinkElements& xml_link = found->second;
    const std::vector<const tinyxml2::XMLElement*>& elements = xml_link.collisions;
    if (link->collision_array.size() != elements.size()) {
      collisions_dropped(*xml_link.link, urdf_path, urdfdom_errors);
    }
    for (std::size_t i = 0; i < elements.size(); ++i) {
      const urdf::Collision& collision = *link->collision_array[i];
      const tinyxml2::XMLElement* shape =
          elements[i]->FirstChildElement("geometry")->FirstChildElement();
      const SourceLocation where{urdf_path, shape->GetLineNum(),
                                 "link '" + link->name + "' collision"};
      const TriangleMesh element = collision_geometry(*collision.geometry, urdf_folder, packages,
                                                      where, notices, &robot.mesh_files);
      // Solid where the element's own components are closed (docs/design.md, "Solids").
      const std::vector<std::uint8_t> solid = closed_triangles(mesh_components(element));
      out.collision.append(element, to_isometry(collision.origin));
      out.solid.insert(out.solid.end(), solid.begin(), solid.end());
    }
    if (link->parent_joint) {
      const urdf::Joint& j = *link->parent_joint;
      Joint joint;
      joint.name = j.name;
      joint.type = to_joint_type(j.type);
      joint.parent_link = link_index.at(j.parent_link_name);
      joint.child_link = index;
      joint.X_PJ = to_isometry(j.parent_to_joint_origin_transform);
      const SourceLocation joint_where{urdf_path, line_of(joint_lines, j.name),
                                       "joint '" + j.name + "'"};
      if (joint.is_single_dof() || joint.type == JointType::kPlanar) {
        const Eigen::Vector3d axis(j.axis.x, j.axis.y, j.axis.z);
        if (!axis.allFinite() || axis.norm() < 1e-12) {
          throw InputError(joint_where, "axis must be a non-zero finite vector");
        }
        joint.axis_J = axis.normalized();
      }
      if (joint.type == JointType::kContinuous) {
        joint.lower = -M_PI;
        joint.upper = M_PI;
      } else if (j.limits && joint.is_single_dof()) {
        joint.lower = j.limits->lower;
        joint.upper = j.limits->upper;
        if (!std::isfinite(joint.lower) || !std::isfinite(joint.upper) ||
            joint.lower > joint.upper) {
          throw InputError(joint_where, "limit lower must not exceed upper, both finite");
        }
      } else if (joint.is_single_dof()) {
        throw InputError(joint_where, "a revolute or prismatic joint needs a <limit>");
      }
      if (j.mimic && !joint.is_single_dof()) {
        // Nothing to drive (the Panda of MotionBenchMaker puts one on a fixed finger):
        // MoveIt and urdfdom ignore it; so do we, saying so.
        if (notices) {
          notices->push_back(urdf_path + ":" + std::to_string(line_of(joint_lines, joint.name)) +
                             ": joint '" + joint.name + "' mimic: a <mimic> on a " +
                             joint_type_name(joint.type) + " joint drives nothing; ignored");
        }
      } else if (j.mimic) {
        joint.mimic_multiplier = j.mimic->multiplier;
        joint.mimic_offset = j.mimic->offset;
        // The master is resolved once all joints are known (it may come later).
        joint.mimic_joint = -2;
      }
      out.parent_joint = static_cast<int>(robot.joints.size());
      robot.joints.push_back(joint);
    }
    robot.links.push_back(std::move(out));
    for (const urdf::LinkSharedPtr& child : link->child_links) queue.push_back(child);
  }
  for (Joint& joint : robot.joints) {
    if (joint.mimic_joint != -2) continue;
    const urdf::JointConstSharedPtr j = model->getJoint(joint.name);
    joint.mimic_joint = robot.find_joint(j->mimic->joint_name);
    const SourceLocation where{urdf_path, line_of(joint_lines, joint.name),
                               "joint '" + joint.name + "' mimic"};
    if (joint.mimic_joint < 0 || !robot.joints[joint.mimic_joint].is_single_dof()) {
      throw InputError(where, "mimics '" + j->mimic->joint_name +
                                  "', which is not a revolute, continuous or prismatic joint "
                                  "of this URDF; name one that is");
    }
    if (robot.joints[joint.mimic_joint].mimic_joint != -1) {
      throw InputError(where,
                       "mimics a joint that itself mimics another; chain them to the "
                       "master instead");
    }
    notice_mimic_range(joint, robot.joints[joint.mimic_joint], where, notices);
  }
  if (robot.triangle_count() == 0) {
    const tinyxml2::XMLElement* root = doc.FirstChildElement("robot");
    throw InputError({urdf_path, root->GetLineNum(), "robot '" + robot.name + "'"},
                     "no link has collision geometry, so nothing can collide; add a <collision> "
                     "with a <geometry> to each link that can hit something");
  }
  robot.disabled_pairs = adjacent_link_pairs(robot);
  return robot;
}

int apply_srdf(RobotModel* robot, const std::string& srdf_path,
               const SourceLocation& referenced_from, std::vector<std::string>* notices) {
  tinyxml2::XMLDocument doc;
  parse_xml_file(srdf_path, kSrdfFile, referenced_from, &doc);
  const tinyxml2::XMLElement* root = doc.RootElement();
  if (root == nullptr || std::string(root->Name()) != "robot") {
    throw InputError({srdf_path, root ? root->GetLineNum() : 0, "robot"},
                     "an SRDF has <robot> as its root element");
  }
  static const std::set<std::string> kCore = {"group",
                                              "group_state",
                                              "end_effector",
                                              "virtual_joint",
                                              "passive_joint",
                                              "disable_collisions",
                                              "disable_default_collisions",
                                              "enable_collisions",
                                              "link_sphere_approximation"};
  std::set<std::string> skipped;
  std::vector<std::string> unknown_links;  // named by disable_collisions, not in the URDF
  int read = 0;
  std::set<std::pair<int, int>> pairs(robot->disabled_pairs.begin(), robot->disabled_pairs.end());
  for (const tinyxml2::XMLElement* e = root->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag != "disable_collisions") {
      if (!kCore.count(tag) && skipped.insert(tag).second && notices) {
        notices->push_back(srdf_path + ":" + std::to_string(e->GetLineNum()) + ": <" + tag +
                           "> is not part of the SRDF format gplanner reads; skipped");
      }
      continue;
    }
    const SourceLocation where{srdf_path, e->GetLineNum(), "disable_collisions"};
    int ends[2];
    const char* attributes[2] = {"link1", "link2"};
    for (int k = 0; k < 2; ++k) {
      const char* name = e->Attribute(attributes[k]);
      if (name == nullptr) {
        throw InputError(where, std::string("missing attribute ") + attributes[k]);
      }
      ends[k] = robot->find_link(name);
      if (ends[k] < 0) {
        unknown_links.push_back(std::string(name) + " (line " + std::to_string(e->GetLineNum()) +
                                ")");
      }
    }
    // A pair naming a link the URDF lacks disables nothing: srdfdom skips it, warning.
    if (ends[0] < 0 || ends[1] < 0) continue;
    ++read;
    if (ends[0] != ends[1]) pairs.emplace(std::min(ends[0], ends[1]), std::max(ends[0], ends[1]));
  }
  if (!unknown_links.empty() && notices) {
    std::string list;
    for (std::size_t i = 0; i < unknown_links.size() && i < 10; ++i)
      list += (i ? ", " : "") + unknown_links[i];
    if (unknown_links.size() > 10)
      list += " and " + std::to_string(unknown_links.size() - 10) + " more";
    notices->push_back(srdf_path + ": " + std::to_string(unknown_links.size()) +
                       " disable_collisions link name(s) that URDF '" + robot->source_file +
                       "' does not have: " + list +
                       "; those pairs are skipped, as srdfdom "
                       "skips them");
  }
  robot->disabled_pairs.assign(pairs.begin(), pairs.end());
  robot->srdf_file = srdf_path;
  return read;
}

namespace {

// The <group name="group"> element of an SRDF, or null.
const tinyxml2::XMLElement* find_group(const tinyxml2::XMLElement* root, const std::string& group) {
  for (const tinyxml2::XMLElement* e = root->FirstChildElement("group"); e;
       e = e->NextSiblingElement("group")) {
    const char* name = e->Attribute("name");
    if (name && group == name) return e;
  }
  return nullptr;
}

// Adds to `joints` the joints of group `g` (the index of each in robot.joints), following
// nested groups (`depth` guards against a group that contains itself).
void collect_group_joints(const RobotModel& robot, const tinyxml2::XMLElement* root,
                          const tinyxml2::XMLElement* g, const std::string& srdf_path, int depth,
                          std::set<int>* joints) {
  if (depth > 32) {
    throw InputError({srdf_path, g->GetLineNum(), "group"},
                     "groups nested more than 32 deep (a group that contains itself?); "
                     "fix the group");
  }
  for (const tinyxml2::XMLElement* e = g->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    const SourceLocation where{srdf_path, e->GetLineNum(), "group " + tag};
    auto attribute = [&](const char* name) {
      const char* value = e->Attribute(name);
      if (value == nullptr) throw InputError(where, std::string("missing attribute ") + name);
      return std::string(value);
    };
    auto link_of = [&](const std::string& name) {
      const int l = robot.find_link(name);
      if (l < 0)
        throw InputError(where, "names link '" + name + "', which URDF '" + robot.source_file +
                                    "' does not have; fix the name or use the matching URDF");
      return l;
    };
    if (tag == "joint") {
      const std::string name = attribute("name");
      const int j = robot.find_joint(name);
      if (j >= 0) {
        joints->insert(j);
      } else {
        // A virtual joint of the SRDF (the robot's base in the world) is no URDF joint.
        bool is_virtual = false;
        for (const tinyxml2::XMLElement* v = root->FirstChildElement("virtual_joint"); v;
             v = v->NextSiblingElement("virtual_joint")) {
          const char* vname = v->Attribute("name");
          is_virtual = is_virtual || (vname && name == vname);
        }
        if (!is_virtual)
          throw InputError(where, "names joint '" + name + "', which URDF '" + robot.source_file +
                                      "' does not have; fix the name");
      }
    } else if (tag == "link") {
      const int l = link_of(attribute("name"));
      if (robot.links[l].parent_joint >= 0) joints->insert(robot.links[l].parent_joint);
    } else if (tag == "chain") {
      const int base = link_of(attribute("base_link"));
      int l = link_of(attribute("tip_link"));
      while (l != base) {
        const int j = robot.links[l].parent_joint;
        if (j < 0) {
          throw InputError(where, "tip_link '" + robot.links[link_of(attribute("tip_link"))].name +
                                      "' does not hang from base_link '" + robot.links[base].name +
                                      "'; give a base_link above the tip");
        }
        joints->insert(j);
        l = robot.joints[j].parent_link;
      }
    } else if (tag == "group") {
      const std::string name = attribute("name");
      const tinyxml2::XMLElement* sub = find_group(root, name);
      if (sub == nullptr)
        throw InputError(where, "names group '" + name + "', which the SRDF lacks");
      collect_group_joints(robot, root, sub, srdf_path, depth + 1, joints);
    }
  }
}

}  // namespace

std::vector<int> srdf_group_joints(const RobotModel& robot, const std::string& srdf_path,
                                   const std::string& group,
                                   const SourceLocation& referenced_from) {
  tinyxml2::XMLDocument doc;
  parse_xml_file(srdf_path, kSrdfFile, referenced_from, &doc);
  const tinyxml2::XMLElement* root = doc.RootElement();
  const tinyxml2::XMLElement* g = root ? find_group(root, group) : nullptr;
  if (g == nullptr) {
    std::string names;
    for (const tinyxml2::XMLElement* e = root ? root->FirstChildElement("group") : nullptr; e;
         e = e->NextSiblingElement("group")) {
      if (e->Attribute("name"))
        names += (names.empty() ? "" : ", ") + std::string(e->Attribute("name"));
    }
    throw InputError(referenced_from, "SRDF '" + srdf_path + "' has no group '" + group +
                                          "'; use one of its groups (" +
                                          (names.empty() ? "it has none" : names) + ")");
  }
  std::set<int> joints;
  collect_group_joints(robot, root, g, srdf_path, 0, &joints);
  std::vector<int> result;
  for (const int j : joints) {  // robot.joints is in tree order, parents first
    if (robot.joints[j].is_single_dof() && robot.joints[j].mimic_joint < 0) result.push_back(j);
  }
  if (result.empty()) {
    throw InputError({srdf_path, g->GetLineNum(), "group '" + group + "'"},
                     "has no joint that takes a value (revolute, continuous or prismatic); "
                     "plan another group");
  }
  return result;
}

}  // namespace gplanner
