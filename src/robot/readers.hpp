#pragma once
// One reader per format, each filling a RobotModel's links and joints from the parsed file (name,
// format, path and text are set by read_robot_model). Each throws InvalidArgument through
// XmlSource::fail (path:line: <element>: what is wrong) for values that are not what the format says.
#include "xml_source.hpp"

namespace tumble::robot {

void read_urdf(const XmlSource& xml, const pugi::xml_node& robot, RobotModel& model);
void read_mjcf(const XmlSource& xml, const pugi::xml_node& mujoco, RobotModel& model);
void read_sdf(const XmlSource& xml, const pugi::xml_node& sdf, RobotModel& model);

}  // namespace tumble::robot
