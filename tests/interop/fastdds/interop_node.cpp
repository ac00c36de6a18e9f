// A ROS 2-like node on Fast DDS (the DDS under ROS 2's default rmw_fastrtps_cpp) for the
// cross-vendor interop test (tests/interop/test_fastdds_interop.py). It subscribes to the
// bridge's ego topics with ROS 2's QoS (reliable, keep last 10; transient local for /map
// and /tf_static) and prints one JSON line per sample it decodes; it publishes /drive
// (20 Hz, like a controller) and /initialpose when told on stdin:
//   drive STEER SPEED | stop | initialpose X Y YAW | quit
// Usage: interop_node DOMAIN_ID. Discovery configuration comes from the XML profile in
// FASTRTPS_DEFAULT_PROFILES_FILE, as for any ROS 2 node on Fast DDS.
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "ros_msgs.h"
#include "ros_msgsPubSubTypes.h"

using namespace eprosima::fastdds::dds;
namespace bi = builtin_interfaces::msg::dds_;
namespace gm = geometry_msgs::msg::dds_;

static std::mutex out_mutex;
static const auto t_start = std::chrono::steady_clock::now();

static double elapsed() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
}

static void emit(const std::string& line) {
    std::lock_guard<std::mutex> lock(out_mutex);
    std::cout << line << std::endl;
}

// Round-trip exact numbers: %.9g for float, %.17g for double.
static std::string f32(float v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.9g", static_cast<double>(v));
    return std::isfinite(v) ? b : "null";
}
static std::string f64(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.17g", v);
    return std::isfinite(v) ? b : "null";
}
static std::string jstr(const std::string& s) {
    std::string o = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') o += '\\';
        o += c;
    }
    return o + "\"";
}
static std::string head(const char* topic, const std_msgs::msg::dds_::Header_& h) {
    return std::string("{\"topic\":\"") + topic + "\",\"t\":" + f64(elapsed()) + ",\"sec\":" +
           std::to_string(h.stamp().sec()) + ",\"nanosec\":" + std::to_string(h.stamp().nanosec()) +
           ",\"frame\":" + jstr(h.frame_id());
}

// Takes every sample of one topic and prints it with `format`.
template <class Msg>
class Printer : public DataReaderListener {
  public:
    using Format = std::string (*)(const Msg&);
    explicit Printer(Format f) : format_(f) {}
    void on_data_available(DataReader* reader) override {
        Msg msg;
        SampleInfo info;
        while (reader->take_next_sample(&msg, &info) == ReturnCode_t::RETCODE_OK) {
            if (info.valid_data) emit(format_(msg));
        }
    }
    void on_subscription_matched(DataReader* reader, const SubscriptionMatchedStatus& s) override {
        emit("{\"event\":\"matched\",\"topic\":\"" + reader->get_topicdescription()->get_name() +
             "\",\"count\":" + std::to_string(s.current_count) + ",\"t\":" + f64(elapsed()) + "}");
    }

  private:
    Format format_;
};

class WriterMatch : public DataWriterListener {
  public:
    void on_publication_matched(DataWriter* w, const PublicationMatchedStatus& s) override {
        emit("{\"event\":\"matched\",\"topic\":\"" + w->get_topic()->get_name() + "\",\"count\":" +
             std::to_string(s.current_count) + ",\"t\":" + f64(elapsed()) + "}");
    }
};

static std::string scan_json(const sensor_msgs::msg::dds_::LaserScan_& m) {
    double sum = 0;
    for (float r : m.ranges()) sum += r;
    const auto& r = m.ranges();
    size_t n = r.size();
    return head("/scan", m.header()) + ",\"n\":" + std::to_string(n) + ",\"angle_min\":" + f32(m.angle_min()) +
           ",\"angle_max\":" + f32(m.angle_max()) + ",\"angle_increment\":" + f32(m.angle_increment()) +
           ",\"scan_time\":" + f32(m.scan_time()) + ",\"range_min\":" + f32(m.range_min()) +
           ",\"range_max\":" + f32(m.range_max()) + ",\"sum\":" + f64(sum) +
           ",\"r0\":" + (n ? f32(r[0]) : "null") + ",\"rmid\":" + (n ? f32(r[n / 2]) : "null") +
           ",\"rlast\":" + (n ? f32(r[n - 1]) : "null") + "}";
}

static std::string odom_json(const nav_msgs::msg::dds_::Odometry_& m) {
    const auto& p = m.pose().pose();
    const auto& t = m.twist().twist();
    return head("/ego_racecar/odom", m.header()) + ",\"child\":" + jstr(m.child_frame_id()) +
           ",\"x\":" + f64(p.position().x()) + ",\"y\":" + f64(p.position().y()) + ",\"z\":" + f64(p.position().z()) +
           ",\"qx\":" + f64(p.orientation().x()) + ",\"qy\":" + f64(p.orientation().y()) +
           ",\"qz\":" + f64(p.orientation().z()) + ",\"qw\":" + f64(p.orientation().w()) +
           ",\"vx\":" + f64(t.linear().x()) + ",\"vy\":" + f64(t.linear().y()) + ",\"wz\":" + f64(t.angular().z()) +
           "}";
}

static std::string map_json(const nav_msgs::msg::dds_::OccupancyGrid_& m) {
    // FNV-1a (64 bit) of the cells, so the test compares the map pixel for pixel.
    uint64_t h = 1469598103934665603ull;
    long free_ = 0, occ = 0, unknown = 0;
    for (char c : m.data()) {
        h = (h ^ static_cast<uint8_t>(c)) * 1099511628211ull;
        int v = static_cast<signed char>(c);
        (v == 0 ? free_ : v < 0 ? unknown : occ)++;
    }
    const auto& o = m.info().origin();
    return head("/map", m.header()) + ",\"width\":" + std::to_string(m.info().width()) +
           ",\"height\":" + std::to_string(m.info().height()) + ",\"resolution\":" + f32(m.info().resolution()) +
           ",\"ox\":" + f64(o.position().x()) + ",\"oy\":" + f64(o.position().y()) +
           ",\"oqz\":" + f64(o.orientation().z()) + ",\"oqw\":" + f64(o.orientation().w()) +
           ",\"cells\":" + std::to_string(m.data().size()) + ",\"fnv\":\"" + std::to_string(h) +
           "\",\"free\":" + std::to_string(free_) + ",\"occupied\":" + std::to_string(occ) +
           ",\"unknown\":" + std::to_string(unknown) + "}";
}

static std::string tf_json(const char* topic, const tf2_msgs::msg::dds_::TFMessage_& m) {
    std::string s = std::string("{\"topic\":\"") + topic + "\",\"t\":" + f64(elapsed()) + ",\"transforms\":[";
    bool first = true;
    for (const auto& t : m.transforms()) {
        const auto& tr = t.transform().translation();
        s += std::string(first ? "" : ",") + "{\"frame\":" + jstr(t.header().frame_id()) +
             ",\"child\":" + jstr(t.child_frame_id()) + ",\"sec\":" + std::to_string(t.header().stamp().sec()) +
             ",\"nanosec\":" + std::to_string(t.header().stamp().nanosec()) + ",\"x\":" + f64(tr.x()) +
             ",\"y\":" + f64(tr.y()) + ",\"z\":" + f64(tr.z()) + "}";
        first = false;
    }
    return s + "]}";
}
static std::string tf_static_json(const tf2_msgs::msg::dds_::TFMessage_& m) { return tf_json("/tf_static", m); }
static std::string tf_dynamic_json(const tf2_msgs::msg::dds_::TFMessage_& m) { return tf_json("/tf", m); }

static std::string clock_json(const rosgraph_msgs::msg::dds_::Clock_& m) {
    return "{\"topic\":\"/clock\",\"t\":" + f64(elapsed()) + ",\"sec\":" + std::to_string(m.clock().sec()) +
           ",\"nanosec\":" + std::to_string(m.clock().nanosec()) + "}";
}

struct Node {
    DomainParticipant* dp = nullptr;
    Publisher* pub = nullptr;
    Subscriber* sub = nullptr;
    WriterMatch writer_match;

    Topic* topic(const std::string& ros_name, TypeSupport type) {
        type.register_type(dp);  // no-op when already registered
        return dp->create_topic("rt" + ros_name, type.get_type_name(), TOPIC_QOS_DEFAULT);
    }
    // ROS 2's default QoS (rmw_qos_profile_default), transient local for latched topics.
    static DataReaderQos reader_qos(bool latched) {
        DataReaderQos q = DATAREADER_QOS_DEFAULT;
        q.reliability().kind = RELIABLE_RELIABILITY_QOS;
        q.history().kind = KEEP_LAST_HISTORY_QOS;
        q.history().depth = 10;
        q.durability().kind = latched ? TRANSIENT_LOCAL_DURABILITY_QOS : VOLATILE_DURABILITY_QOS;
        return q;
    }
    template <class Msg>
    void subscribe(const std::string& name, TypeSupport type, typename Printer<Msg>::Format f, bool latched) {
        sub->create_datareader(topic(name, type), reader_qos(latched), new Printer<Msg>(f));
    }
    DataWriter* publisher(const std::string& name, TypeSupport type) {
        DataWriterQos q = DATAWRITER_QOS_DEFAULT;
        q.reliability().kind = RELIABLE_RELIABILITY_QOS;
        q.history().kind = KEEP_LAST_HISTORY_QOS;
        q.history().depth = 10;
        q.durability().kind = VOLATILE_DURABILITY_QOS;
        return pub->create_datawriter(topic(name, type), q, &writer_match);
    }
};

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: interop_node DOMAIN_ID" << std::endl;
        return 2;
    }
    Node n;
    n.dp = DomainParticipantFactory::get_instance()->create_participant(std::stoi(argv[1]), PARTICIPANT_QOS_DEFAULT);
    if (n.dp == nullptr) {
        std::cerr << "interop_node: cannot create the participant" << std::endl;
        return 1;
    }
    n.pub = n.dp->create_publisher(PUBLISHER_QOS_DEFAULT);
    n.sub = n.dp->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
    TypeSupport scan(new sensor_msgs::msg::dds_::LaserScan_PubSubType());
    TypeSupport odom(new nav_msgs::msg::dds_::Odometry_PubSubType());
    TypeSupport grid(new nav_msgs::msg::dds_::OccupancyGrid_PubSubType());
    TypeSupport tf(new tf2_msgs::msg::dds_::TFMessage_PubSubType());
    TypeSupport clock(new rosgraph_msgs::msg::dds_::Clock_PubSubType());
    TypeSupport drive(new ackermann_msgs::msg::dds_::AckermannDriveStamped_PubSubType());
    TypeSupport pose(new gm::PoseWithCovarianceStamped_PubSubType());
    n.subscribe<sensor_msgs::msg::dds_::LaserScan_>("/scan", scan, scan_json, false);
    n.subscribe<nav_msgs::msg::dds_::Odometry_>("/ego_racecar/odom", odom, odom_json, false);
    n.subscribe<nav_msgs::msg::dds_::OccupancyGrid_>("/map", grid, map_json, true);
    n.subscribe<tf2_msgs::msg::dds_::TFMessage_>("/tf_static", tf, tf_static_json, true);
    n.subscribe<tf2_msgs::msg::dds_::TFMessage_>("/tf", tf, tf_dynamic_json, false);
    n.subscribe<rosgraph_msgs::msg::dds_::Clock_>("/clock", clock, clock_json, false);
    DataWriter* drive_w = n.publisher("/drive", drive);
    DataWriter* pose_w = n.publisher("/initialpose", pose);
    emit("{\"event\":\"ready\",\"t\":" + f64(elapsed()) + "}");

    // The controller: /drive at 20 Hz with the latest command, once one was given.
    std::atomic<bool> running{true}, driving{false};
    std::atomic<float> steer{0.f}, speed{0.f};
    std::thread controller([&] {
        while (running) {
            if (driving) {
                ackermann_msgs::msg::dds_::AckermannDriveStamped_ m;
                m.header().frame_id("ego_racecar/base_link");
                m.drive().steering_angle(steer);
                m.drive().speed(speed);
                drive_w->write(&m);
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
        }
    });
    std::string line;
    while (std::getline(std::cin, line)) {
        std::istringstream in(line);
        std::string cmd;
        in >> cmd;
        if (cmd == "drive") {
            float s = 0, v = 0;
            in >> s >> v;
            steer = s;
            speed = v;
            driving = true;
        } else if (cmd == "stop") {  // one zero command, then no more /drive
            driving = false;
            std::this_thread::sleep_for(std::chrono::milliseconds(60));
            ackermann_msgs::msg::dds_::AckermannDriveStamped_ m;
            m.header().frame_id("ego_racecar/base_link");
            drive_w->write(&m);
        } else if (cmd == "initialpose") {
            double x = 0, y = 0, yaw = 0;
            in >> x >> y >> yaw;
            gm::PoseWithCovarianceStamped_ m;
            m.header().frame_id("map");
            m.pose().pose().position().x(x);
            m.pose().pose().position().y(y);
            m.pose().pose().orientation().z(std::sin(yaw / 2));
            m.pose().pose().orientation().w(std::cos(yaw / 2));
            pose_w->write(&m);
        } else if (cmd == "quit") {
            break;
        }
        emit("{\"event\":\"done\",\"cmd\":" + jstr(cmd) + ",\"t\":" + f64(elapsed()) + "}");
    }
    running = false;
    controller.join();
    n.dp->delete_contained_entities();
    DomainParticipantFactory::get_instance()->delete_participant(n.dp);
    return 0;
}
