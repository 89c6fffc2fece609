// The post-processor against LinuxCNC's own kinematics: the xyzac-trt-kins module (Debian
// package linuxcnc-uspace) is loaded, with the few HAL and RTAPI functions it calls stood in for
// here (its pins kept by name). Its inverse kinematics turns the angles Gcode.hpp chooses into
// joints, the pivot and tool offsets 0: a layer's tool axis must then run along the machine's +Z,
// where the nozzle points from. With its pins set, its joints must be machine_position()'s. An
// executable of its own: the module resolves the stand-ins against it (ENABLE_EXPORTS).
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>
#include <string>

#include "mas/Angles.hpp"
#include "mas/Gcode.hpp"

#ifndef MAS_LINUXCNC_KINS
#define MAS_LINUXCNC_KINS "/usr/lib/linuxcnc/modules/xyzac-trt-kins.so"
#endif

// The module's float pins by name ("xyzac-trt-kins.y-offset", ...).
static std::map<std::string, double*>& float_pins() {
    static std::map<std::string, double*> pins;
    return pins;
}

// What the module calls of HAL and RTAPI. Pins are zeroed memory: rot points and offsets are 0
// until a test sets them, and the kinematics type pin 0 selects the tool-centre-point kinematics
// (trtfuncs.c).
extern "C" {
int hal_init(const char*) { return 1; }
void* hal_malloc(long size) { return std::calloc(1, size < 8 ? 8 : static_cast<size_t>(size)); }
int hal_pin_float_newf(int, double** pin, int, const char* format, ...) {
    *pin = static_cast<double*>(std::calloc(1, sizeof(double)));
    char name[256];
    va_list args;
    va_start(args, format);
    std::vsnprintf(name, sizeof name, format, args);
    va_end(args);
    float_pins()[name] = *pin;
    return 0;
}
int hal_pin_bit_new(const char*, int, void** pin, int) {
    *pin = std::calloc(1, 8);
    return 0;
}
int hal_pin_s32_new(const char*, int, int** pin, int) {
    *pin = static_cast<int*>(std::calloc(1, 8));
    return 0;
}
int hal_ready(int) { return 0; }
int hal_exit(int) { return 0; }
void rtapi_print(const char*, ...) {}
void rtapi_print_msg(int, const char*, ...) {}
}

using mas::kPi;

namespace {

// LinuxCNC's EmcPose: tran (x, y, z), a, b, c, u, v, w.
struct EmcPose {
    double x, y, z, a, b, c, u, v, w;
};
using Inverse = int (*)(const EmcPose*, double*, const unsigned long*, unsigned long*);

// The module's inverse kinematics, loaded and started once; null (and a failure) when it cannot
// be.
Inverse load_inverse() {
    static Inverse inverse = [] {
        void* module = dlopen(MAS_LINUXCNC_KINS, RTLD_NOW | RTLD_GLOBAL);
        EXPECT_NE(module, nullptr) << "cannot load LinuxCNC's kinematics (package "
                                      "linuxcnc-uspace, installed by tools/setup.sh): "
                                   << dlerror();
        if (!module) return Inverse(nullptr);
        auto main = reinterpret_cast<int (*)()>(dlsym(module, "rtapi_app_main"));
        auto found = reinterpret_cast<Inverse>(dlsym(module, "kinematicsInverse"));
        EXPECT_NE(main, nullptr);
        EXPECT_NE(found, nullptr);
        if (!main || !found) return Inverse(nullptr);
        EXPECT_EQ(main(), 0);
        return found;
    }();
    return inverse;
}

// Sets the module's pin `name` (after "xyzac-trt-kins."); fails when it has none such.
void set_pin(const std::string& name, double value) {
    const auto pin = float_pins().find("xyzac-trt-kins." + name);
    ASSERT_NE(pin, float_pins().end()) << name;
    *pin->second = value;
}

void zero_pins() {
    for (auto& pin : float_pins()) *pin.second = 0.0;
}

TEST(LinuxCncKinematics, TheTableAnglesTurnEveryLayersAxisUpToTheNozzle) {
    const Inverse inverse = load_inverse();
    ASSERT_NE(inverse, nullptr);
    zero_pins();

    const double degree = kPi / 180.0;
    std::mt19937 random(11);
    std::uniform_real_distribution<double> tilt(0.0, 100.0), turn(-180.0, 180.0);
    const mas::MachineParams machine;  // A -100 to 50
    double previous_a = 0.0, previous_c = 0.0;
    for (int i = 0; i < 1000; ++i) {
        const double t = tilt(random) * degree, c = turn(random) * degree;
        const Eigen::Vector3d n(std::sin(t) * std::cos(c), std::sin(t) * std::sin(c), std::cos(t));
        mas::TableAngles angles;
        ASSERT_TRUE(mas::table_angles(n, machine, previous_a, previous_c, angles));
        // The joints of a tip at p and at p + n, the table at the same angles.
        const Eigen::Vector3d p(3.0 * i - 40.0, -7.0, 11.0 + i % 13);
        const EmcPose at{p.x(), p.y(), p.z(), angles.a_deg, 0, angles.c_deg, 0, 0, 0};
        const EmcPose along{
            p.x() + n.x(), p.y() + n.y(), p.z() + n.z(), angles.a_deg, 0, angles.c_deg, 0, 0, 0};
        double j0[9] = {0}, j1[9] = {0};
        unsigned long inverse_flags = 0, forward_flags = 0;
        ASSERT_EQ(inverse(&at, j0, &inverse_flags, &forward_flags), 0);
        ASSERT_EQ(inverse(&along, j1, &inverse_flags, &forward_flags), 0);
        const Eigen::Vector3d machine_axis(j1[0] - j0[0], j1[1] - j0[1], j1[2] - j0[2]);
        EXPECT_LE((machine_axis - Eigen::Vector3d::UnitZ()).norm(), 1e-12)
            << "axis " << n.transpose() << " at A " << angles.a_deg << " C " << angles.c_deg;
        EXPECT_EQ(j0[3], angles.a_deg);  // the rotary joints are the words
        EXPECT_EQ(j0[4], angles.c_deg);
        previous_a = angles.a_deg;
        previous_c = angles.c_deg;
    }
}

// machine_position() is the module's joints with its pivot and offsets set: the work offset
// added to the pose, the tool length both on the pose (G43 in force) and on its tool-offset pin
// (motion.tooloffset.z, as LinuxCNC's sample xyzac-trt configuration wires it).
TEST(LinuxCncKinematics, TheMachinePositionIsTheModulesJoints) {
    const Inverse inverse = load_inverse();
    ASSERT_NE(inverse, nullptr);
    ASSERT_EQ(float_pins().size(), 7u);  // x/y/z-rot-point, x/y/z-offset, tool-offset
    std::mt19937 random(5);
    std::uniform_real_distribution<double> place(-150.0, 150.0), angle(-360.0, 360.0);
    for (int i = 0; i < 500; ++i) {
        mas::MachineParams m;
        m.work_offset = {place(random), place(random), place(random)};
        m.rot_point = {place(random), place(random), place(random)};
        m.rot_offset_y_mm = place(random);
        m.rot_offset_z_mm = place(random);
        m.tool_length_mm = i % 5 == 0 ? 0.0 : 0.5 * (place(random) + 150.0);
        set_pin("x-rot-point", m.rot_point.x());
        set_pin("y-rot-point", m.rot_point.y());
        set_pin("z-rot-point", m.rot_point.z());
        set_pin("y-offset", m.rot_offset_y_mm);
        set_pin("z-offset", m.rot_offset_z_mm);
        set_pin("tool-offset", m.tool_length_mm);
        const Eigen::Vector3d p(place(random), place(random), place(random));
        const mas::TableAngles angles{angle(random), angle(random)};
        const Eigen::Vector3d w = p + m.work_offset;
        const EmcPose pose{w.x(), w.y(), w.z() + m.tool_length_mm, angles.a_deg, 0, angles.c_deg, 0,
                           0,     0};
        double joints[9] = {0};
        unsigned long inverse_flags = 0, forward_flags = 0;
        ASSERT_EQ(inverse(&pose, joints, &inverse_flags, &forward_flags), 0);
        const Eigen::Vector3d expected(joints[0], joints[1], joints[2]);
        EXPECT_LE((mas::machine_position(p, angles, m) - expected).norm(), 1e-9)
            << "p " << p.transpose() << " A " << angles.a_deg << " C " << angles.c_deg;
    }
    zero_pins();
}

}  // namespace
