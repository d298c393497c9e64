// srp as a library: parse an instruction with the shipped language model
// (srp::language) and place the UR5's tool with the shipped robot model
// (srp::execution). Prints the plan and the tool position; exits 1 on an error.
#include <cstdlib>
#include <exception>
#include <iostream>

#include "srp/core/DataPaths.h"
#include "srp/execution/RobotModel.h"
#include "srp/language/InstructionParser.h"

int main(int argc, char** argv) {
  try {
    // srp finds its data through SRP_DATA_DIR, else here: the installed package's share/srp.
    if (std::getenv("SRP_DATA_DIR") == nullptr) srp::core::DataPaths::setDataDir(SRP_PACKAGE_DATA_DIR);
    const std::string text = argc > 1 ? argv[1] : "Pick up the cuboid from the blue box and place it in the gray box.";

    const srp::language::InstructionParser parser;  // the shipped model
    const srp::language::TaskPlan plan = parser.parse(text);
    std::cout << "plan of \"" << text << "\":\n" << srp::language::describe(plan);

    const srp::execution::RobotModel ur5 = srp::execution::RobotModel::defaultUr5();
    const srp::execution::JointVector q = srp::execution::JointVector::Zero();
    const Eigen::Vector3d p = ur5.X_base_tcp(q).translation();
    std::cout << ur5.name() << " tcp at q = 0: [" << p.x() << ", " << p.y() << ", " << p.z() << "] m (base frame)\n";
    return plan.steps.empty() ? 1 : 0;
  } catch (const std::exception& e) {
    std::cerr << "srp_consumer: error: " << e.what() << "\n";
    return 1;
  }
}
