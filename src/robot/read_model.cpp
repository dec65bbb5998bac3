// read_robot_model: the format from the root element, then that format's reader.
#include <cstring>

#include <fmt/format.h>

#include "readers.hpp"
#include "tumble/error.hpp"
#include "tumble/mass/input_file.hpp"

namespace tumble::robot {

namespace {

/// The first xacro element or attribute, if any: such a file is a template, not yet a robot.
pugi::xml_node xacro_element(const pugi::xml_node& root) {
  for (const pugi::xml_attribute& a : root.attributes())
    if (std::strncmp(a.name(), "xmlns:xacro", 11) == 0) return root;
  for (const pugi::xml_node& n : root)
    if (n.type() == pugi::node_element && std::strncmp(n.name(), "xacro:", 6) == 0) return n;
  for (const pugi::xml_node& n : root) {
    if (n.type() != pugi::node_element) continue;
    if (const pugi::xml_node inner = xacro_element(n)) return inner;
  }
  return {};
}

}  // namespace

RobotModel read_robot_model(const std::filesystem::path& path) {
  const XmlSource xml(path, read_input_file(path, "robot description"));
  const pugi::xml_node root = xml.document().document_element();
  if (!root)
    throw InvalidArgument(fmt::format("{}: no root element: not a robot description", path.string()));
  if (const pugi::xml_node x = xacro_element(root)) {
    // arm.urdf.xacro expands to arm.urdf; anything else to NAME.expanded.urdf (never onto itself).
    const std::string name = path.filename().string();
    const bool xacro_name = name.size() > 6 && name.ends_with(".xacro");
    std::string expanded = xacro_name ? name.substr(0, name.size() - 6) : path.stem().string() + ".expanded";
    if (!expanded.ends_with(".urdf")) expanded += ".urdf";
    xml.fail(x, fmt::format("this is a xacro template, not yet a robot description: expand it first, e.g. "
                            "`xacro {0} > {1}` (ROS) or `python3 -m xacro {0} -o {1}`, and give tumble {1}",
                            name, expanded));
  }
  RobotModel model;
  model.path = path;
  model.text = xml.text();
  const std::string name = root.name();
  if (name == "robot") {
    model.format = Format::urdf;
    read_urdf(xml, root, model);
  } else if (name == "mujoco") {
    model.format = Format::mjcf;
    read_mjcf(xml, root, model);
  } else if (name == "sdf") {
    model.format = Format::sdf;
    read_sdf(xml, root, model);
  } else {
    xml.fail(root,
             "is not a robot description's root: tumble reads URDF (<robot>), MJCF (<mujoco>) and "
             "SDF (<sdf>)");
  }
  return model;
}

}  // namespace tumble::robot
