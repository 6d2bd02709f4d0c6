// friend_urdf: prints the URDF of the FRIEND robot generated from its DH description (of a robot
// with its own URDF, e.g. config/six_axis: that URDF, robot_description::writeUrdf), for the
// robot_description parameter (launch: <param name="robot_description" command="rosrun friend_hw_sim
// friend_urdf --true-error ..."/>).
//   friend_urdf [--description robot.yaml] [--true-error true_error.yaml] [--seed N] [--magnitude K] [--name NAME]
#include <iostream>
#include <string>

#include "friend_hw_sim/true_robot.h"
#include "robot_description/robot_model.h"
#include "robot_description/urdf_writer.h"
#include "imagenets/package_file.h"

int main(int argc, char** argv) {
  std::string description = imagenets::packageFile("friend_description", "config/robot.yaml"), error_file, name;
  int seed = -1;
  double magnitude = 1.0;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw std::runtime_error("option " + a + " expects a value");
        return argv[++i];
      };
      if (a == "--description") description = value();
      else if (a == "--true-error") error_file = value();
      else if (a == "--seed") seed = std::stoi(value());
      else if (a == "--magnitude") magnitude = std::stod(value());
      else if (a == "--name") name = value();
      else if (a == "-h" || a == "--help") {
        std::cout << "usage: friend_urdf [--description robot.yaml] [--true-error true_error.yaml] [--seed N] [--magnitude K] [--name NAME]\n"
                     "Prints the URDF of the nominal robot, or of the simulator's true robot with --true-error.\n";
        return 0;
      } else if (a.rfind("__", 0) == 0) continue;  // roslaunch remapping arguments
      else throw std::runtime_error("unknown argument '" + a + "' (see --help)");
    }
    const auto nominal = robot_description::loadRobotDescription(description);
    auto robot = nominal;
    if (!error_file.empty()) robot = friend_hw_sim::applyTrueError(nominal, friend_hw_sim::loadTrueError(error_file, nominal, seed, magnitude));
    // A robot with its own URDF gets that URDF (its names) with the true robot's error written in.
    std::cout << robot_description::writeUrdf(nominal, robot, name);
  } catch (const std::exception& e) {
    std::cerr << "friend_urdf: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
