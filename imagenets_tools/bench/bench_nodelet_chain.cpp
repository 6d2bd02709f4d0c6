// bench_nodelet_chain: a 1024x768 image through a chain of 5 block nodelets, all in one nodelet
// manager (messages pass by pointer), versus the same chain as 5 plain hand-written nodelets doing
// the same work in one manager (no BlockNodelet host: read the image through cv_bridge, publish the
// same pointer), versus the block chain as 5 separate processes (TCPROS). Prints median and p99
// latency, end to end and per hop, and throughput, side by side with their ratios: the host's cost
// per hop is block / plain. The block and plain chains are loaded together and measured in turns,
// so that the machine's load hits both alike: latency image by image (block, plain, plain, block,
// ...), throughput in rounds (the median of the rounds' ratios, their spread and the CPU time per
// image say how far to trust it). As root,
// also the block chain as 5 processes on two hosts (network namespaces made by scripts/two-hosts:
// blocks 1, 3, 5 on the "robot", the driver and blocks 2, 4 on the "workstation"), so every hop
// crosses the veth between them: the price of splitting a net over machines (docs/launch.md).
// Starts its own ROS master on a private port; needs no sourced environment.
//
// The blocks are imagenets/Grayscale fed a mono8 image, which they check and pass on unchanged (by
// pointer), so the figures are the cost of the links themselves, not of image processing.
#include <errno.h>
#include <time.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <memory>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <nodelet/loader.h>
#include <nodelet/nodelet.h>
#include <cv_bridge/cv_bridge.h>
#include <ros/ros.h>
#include <sensor_msgs/image_encodings.h>
#include <sensor_msgs/Image.h>

#include "imagenets/bench_summary.h"

namespace {

using imagenets::printSummaryRow;

constexpr int kBlocks = 5;
constexpr int kHops = kBlocks + 1;  // driver -> block 1 -> ... -> block 5 -> driver
// In one manager, per chain: latency samples, one image in flight, block and plain taking turns
// image by image; throughput in kRounds rounds, the two chains taking turns round by round.
constexpr int kLatencySamples = 30000;
constexpr int kThroughputMessages = 20000;
constexpr int kRounds = 20;
constexpr int kWindow = 2;  // messages in flight during the throughput run
// One process per block (TCPROS, ~15x slower per image): fewer.
constexpr int kProcessLatencySamples = 300;
constexpr int kProcessThroughputMessages = 2000;
constexpr const char* kRobotIp = "10.77.0.1";  // scripts/two-hosts
constexpr const char* kWorkstationIp = "10.77.0.2";

using Clock = std::chrono::steady_clock;

pid_t spawn(const std::vector<std::string>& args, bool quiet) {
  pid_t pid = fork();
  if (pid == 0) {
    if (quiet) {
      FILE* null = std::fopen("/dev/null", "w");
      if (null) {
        dup2(fileno(null), STDOUT_FILENO);
        dup2(fileno(null), STDERR_FILENO);
      }
    }
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execvp(argv[0], argv.data());
    _exit(127);
  }
  return pid;
}

void stop(pid_t pid) {
  if (pid <= 0) return;
  kill(pid, SIGINT);
  for (int i = 0; i < 50; ++i) {
    if (waitpid(pid, nullptr, WNOHANG) == pid) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
}

struct Figures {
  std::vector<double> latency_us;  // end to end, one message in flight
  std::vector<size_t> round_ends;  // where each round's samples end in latency_us (chains timed in rounds)
  std::vector<double> throughput;  // messages per second with kWindow in flight, one per round
  std::vector<double> cpu_us;      // this process's CPU time per image in those runs, one per round
  std::vector<double> faults;      // this process's page faults per image in those runs, one per round
  int lost = 0;
  bool same_pointer = false;       // the image came back as the object sent
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  size_t i = static_cast<size_t>(p * (v.size() - 1) + 0.5);
  return v[std::min(i, v.size() - 1)];
}

// All threads of this process (driver, spinner, both managers' workers): while one chain runs the
// other waits idle, so what one run adds is that chain's cost. Far steadier than wall time on a
// machine that is not idle.
long processPageFaults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt + u.ru_majflt;
}

double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + t.tv_nsec * 1e-9;
}

// Sends images into `in_topic` and times their arrival on `out_topic`.
class Driver {
 public:
  Driver(const std::string& in_topic, const std::string& out_topic) {
    ros::NodeHandle nh;
    pub_ = nh.advertise<sensor_msgs::Image>(in_topic, 10);
    sub_ = nh.subscribe(out_topic, 10, &Driver::onImage, this, ros::TransportHints().tcpNoDelay());
    image_ = boost::make_shared<sensor_msgs::Image>();
    image_->width = 1024;
    image_->height = 768;
    image_->encoding = "mono8";
    image_->step = 1024;
    image_->data.assign(1024 * 768, 128);
  }

  // Until images make it through the whole chain (connections are set up lazily).
  void warmUp() {
    int warm = 0;
    for (int i = 0; i < 200 && warm < 20; ++i) warm += sendAndWait(0.5) >= 0 ? 1 : 0;
    if (warm == 0) {
      std::fprintf(stderr, "no image came through the chain\n");
      std::exit(1);
    }
  }

  void latency(int samples, Figures* f) {
    for (int i = 0; i < samples; ++i) {
      double us = sendAndWait(2.0);
      if (us < 0) ++f->lost;
      else f->latency_us.push_back(us);
    }
    f->same_pointer = last_same_pointer_;
  }

  // Keeps kWindow images in flight until `messages` came back (or were given up on).
  void throughput(int messages, Figures* f) {
    const auto start = Clock::now();
    const double cpu_start = processCpuSeconds();
    const long faults_start = processPageFaults();
    int sent = 0, done_before;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_before = received_;
    }
    while (sent < messages) {
      std::unique_lock<std::mutex> lock(mutex_);
      if (!cv_.wait_for(lock, std::chrono::seconds(2), [&] { return sent - (received_ - done_before) < kWindow; })) {
        ++f->lost;
        done_before -= 1;  // give up on one message in flight
        continue;
      }
      lock.unlock();
      publish();
      ++sent;
    }
    std::unique_lock<std::mutex> lock(mutex_);
    cv_.wait_for(lock, std::chrono::seconds(2), [&] { return received_ - done_before >= sent; });
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    const int done = received_ - done_before;
    f->throughput.push_back(done / seconds);
    f->cpu_us.push_back(done > 0 ? (processCpuSeconds() - cpu_start) * 1e6 / done : 0.0);
    f->faults.push_back(done > 0 ? static_cast<double>(processPageFaults() - faults_start) / done : 0.0);
  }

  Figures run(int latency_samples, int throughput_messages) {
    Figures f;
    warmUp();
    latency(latency_samples, &f);
    throughput(throughput_messages, &f);
    return f;
  }

 private:
  void publish() {
    auto image = boost::make_shared<sensor_msgs::Image>(*image_);  // a fresh message each time
    image->header.stamp = ros::Time::now();
    sensor_msgs::ImageConstPtr sent = image;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      in_flight_ = sent;
      sent_at_ = Clock::now();
    }
    pub_.publish(sent);
  }

  // End-to-end microseconds, or -1 when nothing came back in time.
  double sendAndWait(double timeout) {
    int before;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      before = received_;
    }
    publish();
    std::unique_lock<std::mutex> lock(mutex_);
    if (!cv_.wait_for(lock, std::chrono::duration<double>(timeout), [&] { return received_ > before; })) return -1;
    return std::chrono::duration<double, std::micro>(received_at_ - sent_at_).count();
  }

  void onImage(const sensor_msgs::ImageConstPtr& image) {
    const auto now = Clock::now();
    std::lock_guard<std::mutex> lock(mutex_);
    received_at_ = now;
    last_same_pointer_ = image.get() == in_flight_.get();
    ++received_;
    cv_.notify_all();
  }

  ros::Publisher pub_;
  ros::Subscriber sub_;
  sensor_msgs::ImagePtr image_;
  std::mutex mutex_;
  std::condition_variable cv_;
  sensor_msgs::ImageConstPtr in_flight_;
  Clock::time_point sent_at_, received_at_;
  int received_ = 0;
  bool last_same_pointer_ = false;
};

std::string blockName(const std::string& prefix, int i) { return "/" + prefix + std::to_string(i); }

// What a careful hand-written nodelet does for the same stage as imagenets/Grayscale (the way
// image_pipeline's nodelets read images): the image through cv_bridge, a mono8 image passed on as
// the same pointer, any other converted. No ports, properties, pairing, stats or status.
class PlainGrayscale : public nodelet::Nodelet {
 private:
  void onInit() override {
    ros::NodeHandle& pnh = getPrivateNodeHandle();
    pub_ = pnh.advertise<sensor_msgs::Image>("out/image", 5);
    sub_ = pnh.subscribe("in/image", 5, &PlainGrayscale::onImage, this);
  }
  void onImage(const sensor_msgs::ImageConstPtr& image) {
    cv_bridge::CvImageConstPtr in;
    try {
      in = cv_bridge::toCvShare(image);
    } catch (const cv_bridge::Exception& e) {
      NODELET_ERROR_STREAM(e.what());
      return;
    }
    if (image->encoding == sensor_msgs::image_encodings::MONO8) {
      pub_.publish(image);
      return;
    }
    pub_.publish(cv_bridge::cvtColor(in, sensor_msgs::image_encodings::MONO8)->toImageMsg());
  }
  ros::Publisher pub_;
  ros::Subscriber sub_;
};

// Loads the chain of `type` nodelets named /<prefix>1.. in `manager` (this process: driver and
// nodelets share it) and returns the driver that times it end to end.
std::unique_ptr<Driver> chainInOneManager(nodelet::Loader& manager, const std::string& type, const std::string& prefix) {
  const std::string in = "/bench/" + prefix + "_in";
  for (int i = 1; i <= kBlocks; ++i) {
    const std::string name = blockName(prefix, i);
    nodelet::M_string remap{{name + "/in/image", i == 1 ? in : blockName(prefix, i - 1) + "/out/image"}};
    if (!manager.load(name, type, remap, {})) {
      std::fprintf(stderr, "could not load %s as a nodelet (plug-in path?)\n", type.c_str());
      std::exit(1);
    }
  }
  return std::make_unique<Driver>(in, blockName(prefix, kBlocks) + "/out/image");
}

// The block chain and the plain chain, both loaded at once and measured in turns, so a change in
// the machine's load during the run hits both alike: kRounds rounds (which goes first alternates),
// each timing latency image by image in turns, then the throughput of one chain and the other.
// Each round's throughput ratio is one sample; the median and the spread of those samples are what
// the benchmark reports.
void blockAndPlainInOneManager(Figures* block, Figures* plain) {
  nodelet::Loader block_manager(false);
  // The plain nodelets are created directly (no plug-in lookup).
  const boost::function<boost::shared_ptr<nodelet::Nodelet>(const std::string&)> create =
      [](const std::string&) { return boost::shared_ptr<nodelet::Nodelet>(new PlainGrayscale); };
  nodelet::Loader plain_manager(create);
  std::unique_ptr<Driver> block_driver = chainInOneManager(block_manager, "imagenets/Grayscale", "m");
  std::unique_ptr<Driver> plain_driver = chainInOneManager(plain_manager, "bench/PlainGrayscale", "h");
  block_driver->warmUp();
  plain_driver->warmUp();
  for (int r = 0; r < kRounds; ++r) {
    std::pair<Driver*, Figures*> turns[2] = {{block_driver.get(), block}, {plain_driver.get(), plain}};
    if (r % 2 == 1) std::swap(turns[0], turns[1]);
    for (int i = 0; i < kLatencySamples / kRounds; ++i) {
      for (auto& turn : turns) turn.first->latency(1, turn.second);
    }
    for (auto& turn : turns) turn.second->round_ends.push_back(turn.second->latency_us.size());
    for (auto& turn : turns) turn.first->throughput(kThroughputMessages / kRounds, turn.second);
  }
}

// The chain as one process per block. With `robot_namespace`, blocks 1, 3 and 5 run there (this
// process runs in the other host's namespace), so every hop crosses between the two hosts.
Figures inSeparateProcesses(const std::string& prefix, const std::string& robot_namespace = "") {
  std::vector<pid_t> pids;
  for (int i = 1; i <= kBlocks; ++i) {
    const std::string name = blockName(prefix, i);
    const std::string input = i == 1 ? "/bench/" + prefix + "_in" : blockName(prefix, i - 1) + "/out/image";
    std::vector<std::string> command{"/usr/lib/nodelet/nodelet", "standalone", "imagenets/Grayscale",
                                     "__name:=" + name.substr(1), name + "/in/image:=" + input};
    if (!robot_namespace.empty() && i % 2 == 1) {
      const std::vector<std::string> on_robot{"ip", "netns", "exec", robot_namespace, "env", "-u", "ROS_HOSTNAME",
                                              std::string("ROS_IP=") + kRobotIp};
      command.insert(command.begin(), on_robot.begin(), on_robot.end());
    }
    pids.push_back(spawn(command, true));
  }
  Figures f;
  {
    Driver driver("/bench/" + prefix + "_in", blockName(prefix, kBlocks) + "/out/image");
    f = driver.run(kProcessLatencySamples, kProcessThroughputMessages);
  }
  for (pid_t pid : pids) stop(pid);
  return f;
}

// Where two network namespaces can be made (as root, not in a chroot or an unprivileged container):
// makes the two hosts and runs this benchmark again on the workstation (which then measures
// everything, the two-host chain included); removes the hosts when it ends. Returns false (and
// `two-hosts check` says why) when it cannot: the benchmark then runs on one host only.
bool runOnTwoHosts(char** argv, int* status) {
  if (std::getenv("IMAGENETS_BENCH_HOSTS")) return false;  // already on the workstation
  const std::string two_hosts = std::string(IMAGENETS_SOURCE_DIR) + "/scripts/two-hosts";
  if (std::system((two_hosts + " check").c_str()) != 0) {
    std::printf("(two hosts not measured: two network namespaces cannot be made here, see above)\n\n");
    return false;
  }
  const std::string id = "imagenets-bench-" + std::to_string(getpid());
  if (std::system((two_hosts + " up " + id).c_str()) != 0) return false;
  setenv("IMAGENETS_BENCH_HOSTS", id.c_str(), 1);
  signal(SIGINT, [](int) {});  // Ctrl-C ends the run on the workstation; then remove the hosts
  pid_t child = spawn({"ip", "netns", "exec", id + "-workstation", "env", "-u", "ROS_HOSTNAME",
                       std::string("ROS_IP=") + kWorkstationIp, argv[0]},
                      false);
  int wstatus = 0;
  while (waitpid(child, &wstatus, 0) < 0 && errno == EINTR) {
  }
  std::system((two_hosts + " down " + id).c_str());
  *status = WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : 1;
  return true;
}

// Runs again through the catkin devel environment so pluginlib finds the imagenets plug-ins.
void ensureEnvironment(char** argv) {
  if (std::getenv("IMAGENETS_BENCH_ENV")) return;
  setenv("IMAGENETS_BENCH_ENV", "1", 1);
  const std::string path = std::string("/usr/bin:") + (std::getenv("PATH") ? std::getenv("PATH") : "");
  setenv("PATH", path.c_str(), 1);  // Debian's python for the master
  // A steady stream's images come and go at one size. glibc's default hands the freed heap top back
  // to the kernel now and then and faults it in again for the next image: tens of thousands of
  // page faults a run, more of them in the block chain (its blocks keep their last input, for
  // re-runs), +-20 % CPU per image from run to run. Both chains run with the heap kept, as a
  // long-running manager's would be; GLIBC_TUNABLES= (empty) measures with glibc's default.
  setenv("GLIBC_TUNABLES", "glibc.malloc.trim_threshold=268435456:glibc.malloc.mmap_threshold=33554432", 0);
  const std::string env_sh = std::string(IMAGENETS_DEVEL_PREFIX) + "/env.sh";
  execl(env_sh.c_str(), env_sh.c_str(), argv[0], static_cast<char*>(nullptr));
  std::perror(env_sh.c_str());
  std::exit(1);
}

// Starts a ROS master on a private port (and this process's node): false if it does not come up.
bool startMaster(int argc, char** argv, const char* hosts, pid_t* master) {
  const int port = 11800 + static_cast<int>(getpid() % 1000);
  const std::string uri = std::string("http://") + (hosts ? kWorkstationIp : "localhost") + ":" + std::to_string(port);
  setenv("ROS_MASTER_URI", uri.c_str(), 1);
  if (!std::getenv("ROS_HOSTNAME") && !std::getenv("ROS_IP")) setenv("ROS_HOSTNAME", "localhost", 1);
  *master = spawn({"rosmaster", "--core", "-p", std::to_string(port)}, true);
  ros::init(argc, argv, "bench_nodelet_chain", ros::init_options::NoSigintHandler);
  for (int i = 0; i < 100 && !ros::master::check(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  if (ros::master::check()) return true;
  std::fprintf(stderr, "the ROS master did not start\n");
  stop(*master);
  return false;
}

// Percentile `p` of the end-to-end latency (per hop: / kHops). For chains timed in rounds, the
// median of the rounds' own percentiles: a burst of load that hits one round moves one sample,
// not the whole tail.
double latencyAt(const Figures& f, double p, bool per_hop) {
  const double scale = per_hop ? 1.0 / kHops : 1.0;
  if (f.round_ends.size() < 2) return percentile(f.latency_us, p) * scale;
  std::vector<double> of_rounds;
  size_t begin = 0;
  for (size_t end : f.round_ends) {
    of_rounds.push_back(percentile({f.latency_us.begin() + begin, f.latency_us.begin() + end}, p));
    begin = end;
  }
  return percentile(of_rounds, 0.5) * scale;
}

double ratio(double a, double b) { return b > 0 ? a / b : 0.0; }

// Latency rows, median and p99, end to end and per hop. Columns: block nodelets in one manager,
// plain nodelets (ratio block / plain: the host's cost), one process per block (ratio processes /
// block), and with `hosts` the processes alternating between the two hosts (ratio two hosts / block).
void printLatency(const Figures& manager, const Figures& plain, const Figures& processes, const Figures& two_hosts,
                  bool hosts) {
  std::printf("%-24s %14s %14s %8s %12s %8s", "", "block nodelets", "plain nodelets", "ratio", "processes", "ratio");
  if (hosts) std::printf(" %12s %8s", "2 hosts", "ratio");
  std::printf("\n");
  auto row = [&](const std::string& label, double block, double hand, double procs, double across) {
    std::printf("%-24s %14.1f %14.1f %7.2fx %12.1f %7.1fx", label.c_str(), block, hand, ratio(block, hand), procs,
                ratio(procs, block));
    if (hosts) std::printf(" %12.1f %7.1fx", across, ratio(across, block));
    std::printf("\n");
  };
  for (bool per_hop : {false, true}) {
    for (double p : {0.5, 0.99}) {
      auto at = [&](const Figures& f) { return latencyAt(f, p, per_hop); };
      const std::string label = std::string(p == 0.5 ? "median" : "p99") + (per_hop ? " per hop (us)" : " end-to-end (us)");
      row(label, at(manager), at(plain), at(processes), at(two_hosts));
      if (per_hop) {
        printSummaryRow(std::string("nodelet chain, ") + (p == 0.5 ? "median" : "p99") +
                            " latency per hop, us: block nodelets vs plain nodelets, same manager",
                        at(manager), at(plain), "<= 1.1x", at(manager) <= 1.1 * at(plain));
      }
    }
  }
}

// Throughput, CPU per image, and what the chains delivered.
void printThroughput(const Figures& manager, const Figures& plain, const Figures& processes, const Figures& two_hosts,
                     bool hosts) {
  const double block_rate = percentile(manager.throughput, 0.5), plain_rate = percentile(plain.throughput, 0.5);
  const double procs_rate = percentile(processes.throughput, 0.5), hosts_rate = percentile(two_hosts.throughput, 0.5);
  std::printf("%-24s %14.1f %14.1f %7.2fx %12.1f %7.2fx", "throughput (images/s)", block_rate, plain_rate,
              ratio(block_rate, plain_rate), procs_rate, ratio(procs_rate, block_rate));
  if (hosts) std::printf(" %12.2f %7.2fx", hosts_rate, ratio(hosts_rate, block_rate));
  // One ratio per round, block and plain measured back to back: their median and spread.
  std::vector<double> round_ratios;
  for (size_t r = 0; r < manager.throughput.size() && r < plain.throughput.size(); ++r)
    round_ratios.push_back(ratio(manager.throughput[r], plain.throughput[r]));
  const double cpu_block = percentile(manager.cpu_us, 0.5), cpu_plain = percentile(plain.cpu_us, 0.5);
  std::printf("\n%-24s %14.1f %14.1f %7.2fx", "CPU per image (us)", cpu_block, cpu_plain, ratio(cpu_block, cpu_plain));
  std::printf("\n%-24s %14.1f %14.1f", "page faults per image", percentile(manager.faults, 0.5),
              percentile(plain.faults, 0.5));
  std::printf("\n%-24s %14s %14s %7.2fx   (%zu rounds: min %.2fx, max %.2fx; target >= 0.9x)",
              "throughput, per round", "", "", percentile(round_ratios, 0.5), round_ratios.size(),
              percentile(round_ratios, 0.0), percentile(round_ratios, 1.0));
  std::printf("\n%-24s %14s %14s %8s %12s %8s", "same object received", manager.same_pointer ? "yes" : "no",
              plain.same_pointer ? "yes" : "no", "", processes.same_pointer ? "yes" : "no", "");
  if (hosts) std::printf(" %12s", two_hosts.same_pointer ? "yes" : "no");
  std::printf("\n%-24s %14d %14d %8s %12d %8s", "lost images", manager.lost, plain.lost, "", processes.lost, "");
  if (hosts) std::printf(" %12d", two_hosts.lost);
  std::printf("\n");
  printSummaryRow("nodelet chain, throughput images/s (median of rounds): block nodelets vs plain nodelets", block_rate,
                  plain_rate, "", false);
  // The target is judged on the rounds' own ratios: block and plain measured back to back.
  const double round_ratio = percentile(round_ratios, 0.5);
  printSummaryRow("nodelet chain, throughput block / plain nodelets, median of the rounds' ratios", round_ratio, NAN,
                  ">= 0.9", round_ratio >= 0.9);
  printSummaryRow("nodelet chain, CPU us per image: block nodelets vs plain nodelets", cpu_block, cpu_plain, "", false);
}

}  // namespace

int main(int argc, char** argv) {
  ensureEnvironment(argv);
  int status = 0;
  if (runOnTwoHosts(argv, &status)) return status;
  const char* hosts = std::getenv("IMAGENETS_BENCH_HOSTS");
  pid_t master = 0;
  if (!startMaster(argc, argv, hosts, &master)) return 1;
  ros::AsyncSpinner spinner(2);
  spinner.start();

  Figures manager, plain;
  blockAndPlainInOneManager(&manager, &plain);
  Figures processes = inSeparateProcesses("p");
  Figures two_hosts;
  if (hosts) two_hosts = inSeparateProcesses("r", std::string(hosts) + "-robot");

  std::printf("1024x768 mono8 image (768 KiB) through %d imagenets/Grayscale block nodelets (they pass mono8 on);\n"
              "%d topic hops (driver -> blocks -> driver); %d latency samples (one image in flight), %d images for\n"
              "throughput (%d in flight). Per hop = end-to-end / %d.\n\n",
              kBlocks, kHops, kLatencySamples, kThroughputMessages, kWindow, kHops);
  printLatency(manager, plain, processes, two_hosts, hosts != nullptr);
  printThroughput(manager, plain, processes, two_hosts, hosts != nullptr);
  std::printf("\nratio = block nodelets / plain nodelets (latency: the host's cost per hop, target <= 1.1x;\n"
              "        throughput: target >= 0.9x); processes and 2 hosts ratios = them / block. Block and plain\n"
              "        chains run in turns in %d rounds (latency image by image, throughput a chain at a time); their\n"
              "        figures are the medians of the rounds' own. Plain nodelets read the image through cv_bridge\n"
              "        and pass it on, as the blocks do.\n"
              "        2 hosts: every hop crosses the veth between two network\n"
              "        namespaces (robot 10.77.0.1: blocks 1, 3, 5; workstation 10.77.0.2: driver, blocks 2, 4).\n",
              kRounds);

  spinner.stop();
  ros::shutdown();
  stop(master);
  return 0;
}
