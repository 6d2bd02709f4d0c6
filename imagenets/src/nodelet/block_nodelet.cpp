// The generic nodelet host (see block_nodelet.h for what it offers a launch file).
#include "imagenets/block_nodelet.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <set>

#include <dynamic_reconfigure/Reconfigure.h>
#include <console_bridge/console.h>
#include <pluginlib/class_loader.hpp>
#include <imagenets/BlockNodeletStatus.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "imagenets/block_invocation.h"
#include "imagenets/executor.h"
#include "imagenets/net.h"
#include "imagenets/registry.h"
#include "imagenets/inner_net.h"
#include "host_options.h"
#include "input_pairing.h"
#include "imagenets/param_text.h"
#include "reconfigure.h"

namespace imagenets {

// A manager loads only the library of the nodelet it was asked for: load every library that
// declares block nodelets, in whatever package (once per process; kept loaded).
void loadBlockLibraries() {
  static std::mutex mutex;
  static pluginlib::ClassLoader<nodelet::Nodelet>* loader = nullptr;  // never unloaded
  std::lock_guard<std::mutex> lock(mutex);
  if (loader) return;
  loader = new pluginlib::ClassLoader<nodelet::Nodelet>("nodelet", "nodelet::Nodelet");
  // class_loader would print its debug lines (on stdout, at exit too) once a loader exists.
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_WARN);
  std::set<std::string> done;
  for (const std::string& cls : loader->getDeclaredClasses()) {
    if (loader->getClassType(cls).rfind("imagenets::BlockNodelet<", 0) != 0) continue;
    try {
      if (!done.insert(loader->getClassLibraryPath(cls)).second) continue;
      loader->loadLibraryForClass(cls);
    } catch (const std::exception& e) {
      // e.g. the test nodelets' library, built by `make tests` only and never installed
      ROS_DEBUG_STREAM("block library of " << cls << " not loaded: " << e.what());
    }
  }
}

namespace {
// Any program with the nodelet layer (a nodelet manager, the tool, the Designer, a node running
// nets) finds the blocks of every package's library through pluginlib when it meets a type it
// does not know, or when it lists all blocks.
const bool kLibraryLoaderSet = (BlockRegistry::instance().setLibraryLoader(loadBlockLibraries), true);
}  // namespace

class BlockHost {
 public:
  BlockHost(std::function<std::unique_ptr<Block>()> factory, std::string name, ros::NodeHandle pnh)
      : factory_(std::move(factory)), block_(factory_()), name_(std::move(name)), pnh_(pnh) {
    const BlockInfo* info = BlockRegistry::instance().findByTypeId(typeid(*block_));
    if (info) block_->setInfo(info);
    type_ = info ? info->type : std::string("?");
    inner_ = dynamic_cast<const InnerNet*>(block_.get());
    host_ = std::make_unique<HostOptions>(*block_, inner_ != nullptr);
  }

  // Loads properties, configures the block and opens its topics and services. Throws (after
  // logging the named errors) when the nodelet must not load.
  void start() {
    std::vector<std::string> errors = loadParameters();
    if (errors.empty()) {
      try {
        block_->configure();
      } catch (const std::exception& e) {
        errors.push_back(e.what());
      }
    }
    if (!errors.empty()) {
      std::string text = describe() + ": not loaded:";
      for (const auto& e : errors) text += "\n  " + e;
      ROS_ERROR_STREAM(text);
      throw std::runtime_error(text);
    }
    allSpecs();  // the block's ports and properties are final now
    properties_ = block_->propertySnapshot();

    // A source: no required input and no input linked (remapped). It runs once, on a timer or on
    // ~run; any other block runs when its inputs arrive.
    std::vector<bool> required;
    bool linked = false;
    for (const PortSpec& p : block_->inputs()) {
      required.push_back(!p.optional);
      linked = linked || !p.optional || pnh_.resolveName("in/" + p.name) != pnh_.getNamespace() + "/in/" + p.name;
    }
    pairing_ = std::make_unique<InputPairing>(required, host_->pairing(), !linked);
    cached_inputs_.resize(block_->inputs().size());

    const bool latch = host_->latch() || (pairing_->isSource() && host_->sourceMode() == "once");
    const uint32_t queue = host_->queueSize();
    for (const PortSpec& p : block_->outputs()) publishers_.push_back(p.type->advertise(pnh_, "out/" + p.name, queue, latch));
    for (size_t i = 0; i < block_->inputs().size(); ++i) {
      const PortSpec& p = block_->inputs()[i];
      subscribers_.push_back(p.type->subscribe(pnh_, "in/" + p.name, queue, [this, i](const Value& v) { onInput(i, v); }));
    }

    // ~status is built only while someone listens (a message per run costs a chain of cheap
    // blocks ~10 % of its latency); whoever connects gets the current one at once. The listeners
    // are counted here: Publisher::getNumSubscribers takes roscpp's topic lock, which the next
    // block of a chain needs at that moment for its own publish.
    status_pub_ = pnh_.advertise<imagenets::BlockNodeletStatus>(
        "status", 1,
        [this](const ros::SingleSubscriberPublisher&) {
          ++status_listeners_;
          publishStatus();
        },
        [this](const ros::SingleSubscriberPublisher&) { --status_listeners_; }, ros::VoidConstPtr(), true);
    descriptions_pub_ = pnh_.advertise<dynamic_reconfigure::ConfigDescription>("parameter_descriptions", 1, true);
    updates_pub_ = pnh_.advertise<dynamic_reconfigure::Config>("parameter_updates", 1, true);
    descriptions_pub_.publish(describeProperties(specs_));
    publishUpdates();
    publishStatus();
    run_srv_ = pnh_.advertiseService("run", &BlockHost::onRunService, this);
    set_srv_ = pnh_.advertiseService("set_parameters", &BlockHost::onSetParameters, this);
    startSource();
    publishInternalPorts();  // advertises the inner ports
    ROS_DEBUG_STREAM(describe() << ": loaded");
  }

 private:
  std::string describe() const { return "nodelet '" + name_ + "' (" + type_ + ")"; }

  // --- properties -------------------------------------------------------------------------

  const std::vector<const PropertySpec*>& allSpecs() {
    if (specs_.empty()) {
      for (const PropertySpec& s : block_->propertySpecs()) specs_.push_back(&s);
      for (const PropertySpec& s : host_->specs()) specs_.push_back(&s);
    }
    return specs_;
  }
  PropertyValues currentValues() const {
    PropertyValues values = block_->propertyValues();
    for (const auto& kv : host_->values()) values[kv.first] = kv.second;
    return values;
  }

  // Sets a block or host property; throws PropertyError.
  void setValue(const std::string& name, const PropertyValue& value) {
    if (block_->findProperty(name)) {
      block_->setProperty(name, value);
    } else {
      host_->set(name, value);
    }
  }
  // The block's properties, then the host's (a block's name hides the host's).
  std::vector<const PropertySpec*> blockAndHostSpecs() const {
    std::vector<const PropertySpec*> specs;
    for (const PropertySpec& s : block_->propertySpecs()) specs.push_back(&s);
    for (const PropertySpec& s : host_->specs()) specs.push_back(&s);
    return specs;
  }

  // Every ~private parameter must name a property and hold a valid value for it.
  std::vector<std::string> loadParameters() {
    std::vector<std::string> errors;
    std::vector<std::string> all;
    ros::param::getParamNames(all);
    const std::string prefix = pnh_.getNamespace() + "/";
    std::set<std::string> names;
    for (const std::string& full : all) {
      if (full.compare(0, prefix.size(), prefix) != 0) continue;
      std::string rest = full.substr(prefix.size());
      names.insert(rest.substr(0, rest.find('/')));
    }
    const std::vector<const PropertySpec*> specs = blockAndHostSpecs();
    for (const std::string& name : names) {
      XmlRpc::XmlRpcValue raw;
      if (!pnh_.getParam(name, raw)) continue;
      try {
        // Relative paths resolve against the working directory; `$(find pkg)/...` works too.
        setValue(name, parseNamedProperty(specs, name, paramText(raw)));
      } catch (const std::exception& e) {
        errors.push_back("parameter '" + prefix + name + "': " + e.what());
      }
    }
    return errors;
  }

  // --- running ------------------------------------------------------------------------------

  void onInput(size_t input, const Value& value) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!pairing_->add(input, value, &arrived_)) return;
    std::swap(cached_inputs_, arrived_);
    have_inputs_ = true;
    runLocked();
    // The previous inputs go only now that the outputs are on their way: this block may hold the
    // last reference to an image, and freeing its buffer is no business of the next block's.
    std::fill(arrived_.begin(), arrived_.end(), Value());
  }

  // Runs the block on the cached inputs (sources: on their optional inputs' latest values) and
  // publishes what it outputs. Returns the error, empty on success.
  std::string runLocked() {
    if (pairing_->isSource()) cached_inputs_ = pairing_->latest();
    {
      std::lock_guard<std::mutex> lock(status_mutex_);
      running_ = true;  // ~status says "running" while inner progress comes in
      progress_.clear();
    }
    // What runs inside the block (a sub-net) reports on ~status while it runs. The thread's CPU
    // clock (two system calls) is read only while ~status is watched, the one place it shows.
    InvocationOptions options{RunChannel{[this](const RunEvent& e) { onInnerEvent(e); }, {}}, {}};
    options.cpu_time = status_listeners_ > 0;
    BlockInvocation run = invokeBlock(*block_, name_, cached_inputs_, properties_, std::move(options));
    {
      std::lock_guard<std::mutex> lock(status_mutex_);
      running_ = false;
      stats_.record(run.status, run.message, run.ms, run.processed, run.cpu_ms);
    }
    if (run.status == BlockStatus::Ok) {
      for (size_t i = 0; i < publishers_.size(); ++i) {
        const Value& out = run.outputs[i];
        if (out) out.type->publish(publishers_[i], out);  // the pointer itself: zero-copy in-manager
      }
    } else {
      ROS_ERROR_STREAM(run.message);
    }
    publishInternalPorts();
    publishStatus();
    return run.status == BlockStatus::Ok ? std::string() : run.message;
  }

  // An event from inside the block (runLocked holds mutex_), on whichever thread of the inner net
  // ran that inner block: parallel inner blocks report at the same time, hence status_mutex_.
  void onInnerEvent(RunEvent e) {
    if (e.kind == RunEventKind::BlockStarted || e.kind == RunEventKind::RunFinished) return;
    // "<nodelet>/<inner block>" -> "<inner block>"; the block's own events (repetitions) lose the name.
    e.block = e.block.size() > name_.size() ? e.block.substr(name_.size() + 1) : std::string();
    std::lock_guard<std::mutex> lock(status_mutex_);
    progress_ = imagenets::describe(e);
    publishStatusLocked();
  }

  // publish_internal_ports: every inner output port becomes a topic; a value is published only
  // while someone subscribes, and only when it is new (the inner net re-ran that block).
  void publishInternalPorts() {
    if (!inner_ || !host_->publishInternalPorts()) return;
    const Executor* inner = inner_->innerExecutor();
    if (!inner) return;
    if (internal_.empty()) {
      for (const auto& node : inner->net().nodes()) {
        for (const PortSpec& p : node.block->outputs()) {
          internal_.push_back({node.name + "." + p.name,
                               p.type->advertise(pnh_, "internal/" + node.name + "/" + p.name, 1, false), nullptr});
        }
      }
    }
    for (InternalPort& port : internal_) {
      if (port.publisher.getNumSubscribers() == 0) continue;
      const Value v = inner->output(port.block_port);
      if (!v || v.data.get() == port.last_published) continue;
      v.type->publish(port.publisher, v);
      port.last_published = v.data.get();
    }
  }

  bool onRunService(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!have_inputs_ && !pairing_->isSource()) {
      res.success = false;
      res.message = describe() + ": no complete input set received yet";
      return true;
    }
    std::string error = runLocked();
    res.success = error.empty();
    res.message = error.empty() ? "ran " + name_ : error;
    return true;
  }

  void startSource() {
    timer_.stop();
    if (!pairing_->isSource()) return;
    const std::string mode = host_->sourceMode();
    auto tick = [this](const ros::TimerEvent&) {
      std::lock_guard<std::mutex> lock(mutex_);
      runLocked();
    };
    if (mode == "timer") {
      timer_ = pnh_.createTimer(ros::Duration(1.0 / host_->sourceRate()), tick);
    } else if (mode == "once" && !ran_once_) {
      ran_once_ = true;
      // After onInit returns, from the nodelet's own queue (the outputs are latched).
      timer_ = pnh_.createTimer(ros::Duration(0.01), tick, true);
    }
  }

  // --- dynamic_reconfigure ------------------------------------------------------------------

  bool onSetParameters(dynamic_reconfigure::Reconfigure::Request& req,
                       dynamic_reconfigure::Reconfigure::Response& res) {
    std::lock_guard<std::mutex> lock(mutex_);
    PropertyValues block_changes, host_changes;
    const PropertyValues before = currentValues();
    const std::vector<const PropertySpec*> specs = blockAndHostSpecs();
    for (const auto& [name, text] : decodeRequest(req.config)) {
      try {
        PropertyValue v = parseNamedProperty(specs, name, text);
        auto old = before.find(name);
        if (old != before.end() && old->second == v) continue;
        if (findPropertySpec(specs, name).isFixedAtLoad()) {
          throw PropertyError("property '" + name + "': takes effect at load only (the topics are open); reload the "
                              "nodelet to change it");
        }
        (block_->findProperty(name) ? block_changes : host_changes)[name] = v;
      } catch (const std::exception& e) {
        ROS_ERROR_STREAM(describe() << ": set_parameters: " << e.what());
      }
    }
    if (!block_changes.empty() && !reconfigureBlock(block_changes)) block_changes.clear();
    for (const auto& [name, v] : host_changes) host_->set(name, v);
    if (!host_changes.empty()) {
      pairing_->setOptions(host_->pairing());
      startSource();
    }
    for (const auto* changes : {&block_changes, &host_changes}) {
      for (const auto& [name, v] : *changes) pnh_.setParam(name, propertyToParam(v));  // params stay current
    }
    res.config = encodeProperties(specs_, currentValues());
    updates_pub_.publish(res.config);
    // A change re-runs the block on its cached inputs; its outputs refresh everything downstream.
    if (!block_changes.empty() && (have_inputs_ || pairing_->isSource())) runLocked();
    return true;
  }

  // Applies block property changes through a fresh, configured block: properties that configure()
  // reads (a sub-net's `net`) take effect too, and a value configure() rejects leaves the running
  // block as it was. The ports must stay the same, since topics are already wired.
  bool reconfigureBlock(const PropertyValues& changes) {
    std::unique_ptr<Block> fresh = factory_();
    try {
      configureLike(*fresh, *block_, changes);
    } catch (const std::exception& e) {
      ROS_ERROR_STREAM(describe() << ": set_parameters: change refused: " << e.what());
      return false;
    }
    if (!samePorts(*fresh, *block_)) {
      ROS_ERROR_STREAM(describe() << ": set_parameters: change refused: it changes the block's ports; reload the "
                                     "nodelet with the new parameters instead");
      return false;
    }
    block_ = std::move(fresh);
    properties_ = block_->propertySnapshot();
    inner_ = dynamic_cast<const InnerNet*>(block_.get());
    internal_.clear();  // inner ports are advertised again for the new inner net
    specs_.clear();
    allSpecs();
    return true;
  }

  void publishUpdates() { updates_pub_.publish(encodeProperties(specs_, currentValues())); }

  void publishStatus() {
    if (status_listeners_ == 0) return;
    std::lock_guard<std::mutex> lock(status_mutex_);
    publishStatusLocked();
  }
  void publishStatusLocked() {
    if (status_listeners_ == 0) return;
    auto s = boost::make_shared<imagenets::BlockNodeletStatus>();
    s->header.stamp = ros::Time::now();
    s->block = name_;
    s->type = type_;
    s->runs = stats_.runs;
    s->failures = stats_.failures;
    s->last_ms = stats_.last_ms;
    s->mean_ms = stats_.mean_ms;
    s->last_cpu_ms = stats_.last_cpu_ms;
    s->mean_cpu_ms = stats_.mean_cpu_ms;
    s->last_error = stats_.last_error;
    s->status = running_ ? "running" : statusName(stats_.status);
    s->message = stats_.message;
    s->progress = progress_;
    status_pub_.publish(s);
  }

  struct InternalPort {
    std::string block_port;
    ros::Publisher publisher;
    const void* last_published;
  };

  std::function<std::unique_ptr<Block>()> factory_;
  std::unique_ptr<Block> block_;
  // The block's property values, taken when they change (only set_parameters changes them): a
  // run passes them on without the block's lock.
  std::shared_ptr<const PropertyValues> properties_;
  const InnerNet* inner_ = nullptr;  // set for a block running a net inside
  std::vector<InternalPort> internal_;
  std::string name_, type_;
  ros::NodeHandle pnh_;
  std::unique_ptr<HostOptions> host_;
  std::vector<const PropertySpec*> specs_;

  std::mutex mutex_;  // callbacks of one nodelet are serial already; services and timers join them
  std::unique_ptr<InputPairing> pairing_;
  std::vector<Value> cached_inputs_;
  std::vector<Value> arrived_;  // the set being completed, then the previous one until released
  bool have_inputs_ = false;
  bool ran_once_ = false;

  std::vector<ros::Publisher> publishers_;
  std::vector<ros::Subscriber> subscribers_;
  ros::Publisher status_pub_, descriptions_pub_, updates_pub_;
  std::atomic<int> status_listeners_{0};
  ros::ServiceServer run_srv_, set_srv_;
  ros::Timer timer_;

  BlockStats stats_;
  std::mutex status_mutex_;  // guards running_, progress_ and stats_ (read by every ~status publish)
  bool running_ = false;
  std::string progress_;
};

BlockNodeletBase::BlockNodeletBase() = default;
BlockNodeletBase::~BlockNodeletBase() = default;

void BlockNodeletBase::onInit() {
  // A block that builds a net inside (a sub-net) may use any block type: the registry loads the
  // other block libraries when it meets a type it does not know.
  BlockRegistry::instance().setLibraryLoader(loadBlockLibraries);
  host_ = std::make_unique<BlockHost>([this] { return createBlock(); }, getName(), getPrivateNodeHandle());
  try {
    host_->start();
  } catch (...) {
    host_.reset();  // nothing half-open survives; the manager carries on
    throw;
  }
}

}  // namespace imagenets
