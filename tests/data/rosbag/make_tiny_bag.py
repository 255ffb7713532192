#!/usr/bin/python3
"""Writes tiny.bag, the ROS 1 bag tests/apps/test_import.cpp imports (Debian's python3-rosbag,
python3-nav-msgs, python3-sensor-msgs, python3-tf2-msgs). Every value is chosen so that the
test can check it in closed form: run again, it writes the same messages."""
import math
import sys

import rosbag
import rospy
from geometry_msgs.msg import TransformStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan, Range
from std_msgs.msg import String
from tf2_msgs.msg import TFMessage

# s; a second argument moves the clock (0: a bag whose clock starts at 0, test_import.cpp)
T0 = float(sys.argv[2]) if len(sys.argv) > 2 else 1700000000.0


def stamp(t):
    return rospy.Time.from_sec(T0 + t)


def yaw_quaternion(q, yaw):
    q.z, q.w = math.sin(yaw / 2), math.cos(yaw / 2)


out = sys.argv[1] if len(sys.argv) > 1 else "tiny.bag"
with rosbag.Bag(out, "w") as bag:
    # the laser 0.2 m ahead of the base, turned by 0.1 rad: once, latched
    s = TransformStamped()
    s.header.stamp = stamp(0.0)
    s.header.frame_id = "base_link"
    s.child_frame_id = "laser"
    s.transform.translation.x = 0.2
    yaw_quaternion(s.transform.rotation, 0.1)
    bag.write("/tf_static", TFMessage(transforms=[s]), stamp(0.0))
    for k in range(10):  # /odom at 10 Hz: x = 0.1 k m, yaw = 0.05 k rad, 1 m/s
        o = Odometry()
        o.header.stamp = stamp(0.1 * k)
        o.header.frame_id, o.child_frame_id = "odom", "base_link"
        o.pose.pose.position.x = 0.1 * k
        yaw_quaternion(o.pose.pose.orientation, 0.05 * k)
        o.twist.twist.linear.x, o.twist.twist.angular.z = 1.0, 0.5
        bag.write("/odom", o, stamp(0.1 * k))
    for k in range(5):  # /scan at 5 Hz: 5 beams over 180 degrees
        m = LaserScan()
        m.header.stamp = stamp(0.05 + 0.2 * k)
        m.header.frame_id = "laser"
        m.angle_min, m.angle_max = -math.pi / 2, math.pi / 2
        m.angle_increment = math.pi / 4
        m.range_min, m.range_max = 0.1, 10.0
        m.ranges = [1.0, 2.0, float("inf"), 0.05, 3.0 + k]
        bag.write("/scan", m, stamp(0.05 + 0.2 * k))
    for k in range(3):  # /sonar_front: the last has no echo (inf)
        r = Range()
        r.header.stamp = stamp(0.3 * k + 0.01)
        r.header.frame_id = "sonar_front"
        r.radiation_type = Range.ULTRASOUND
        r.field_of_view, r.min_range, r.max_range = 0.5, 0.02, 4.0
        r.range = 1.5 if k < 2 else float("inf")
        bag.write("/sonar_front", r, stamp(0.3 * k + 0.01))
    for k in range(4):  # /tf odom -> base_link at 4 Hz: x = 0.2 k m
        t = TransformStamped()
        t.header.stamp = stamp(0.25 * k + 0.02)
        t.header.frame_id, t.child_frame_id = "odom", "base_link"
        t.transform.translation.x = 0.2 * k
        yaw_quaternion(t.transform.rotation, 0.0)
        bag.write("/tf", TFMessage(transforms=[t]), stamp(0.25 * k + 0.02))
    bag.write("/chatter", String(data="hello"), stamp(0.5))
