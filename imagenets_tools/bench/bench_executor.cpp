// Executor overhead, parallel speed-up and feedback sweep strategies.
// Prints figures; passes or fails nothing.
#include <chrono>
#include <cstdio>
#include <functional>
#include <vector>

#include <malloc.h>

#include <imagenets/FeedbackTrace.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <std_msgs/Float64.h>

#include "imagenets/bench_summary.h"
#include "imagenets/blocks/image.h"
#include "imagenets/executor.h"
#include "imagenets/registry.h"
#include "imagenets/package_file.h"

using namespace imagenets;
using Clock = std::chrono::steady_clock;

namespace {

// The trivial block of the overhead chain: out = in + 1.
boost::shared_ptr<std_msgs::Float64> increment(const std_msgs::Float64& in) {
  auto out = boost::make_shared<std_msgs::Float64>();
  out->data = in.data + 1;
  return out;
}

class Increment : public Block {
 public:
  Increment() {
    addInput<std_msgs::Float64>("in", "x");
    addOutput<std_msgs::Float64>("out", "x + 1");
  }
  void process(Context& ctx) override { ctx.output("out", increment(*ctx.input<std_msgs::Float64>("in"))); }
};

// Median wall time of `fn` over `reps` repetitions, in microseconds.
double medianMicros(int reps, const std::function<void()>& fn) {
  std::vector<double> t;
  for (int i = 0; i < reps; ++i) {
    auto start = Clock::now();
    fn();
    t.push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
  }
  std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
  return t[t.size() / 2];
}

std::unique_ptr<Executor> load(const std::string& yaml, int threads) {
  return std::make_unique<Executor>(Net::build(parseNetText(yaml, "bench.yaml", "")), ExecutorOptions{threads});
}

}  // namespace

IMAGENETS_REGISTER_BLOCK_TYPE(Increment, "bench/Increment", "bench", "x + 1");

namespace {

// A chain of N trivial blocks, executor vs calling the same function N times.
void benchTrivialChain() {
  const int n = 100;
  std::string yaml = "blocks:\n";
  for (int i = 0; i < n; ++i) yaml += "  b" + std::to_string(i) + ": {type: bench/Increment}\n";
  yaml += "links:\n";
  for (int i = 1; i < n; ++i) yaml += "  - b" + std::to_string(i - 1) + ".out -> b" + std::to_string(i) + ".in\n";
  for (int threads : {1, 2}) {
    auto zero = boost::make_shared<std_msgs::Float64>();
    int k = 0;
    // setInput + run(): the whole chain is out of date each time (a new input value).
    auto runChain = [&](Executor& e) {
      zero->data = ++k;
      e.setInput<std_msgs::Float64>("b0.in", boost::shared_ptr<const std_msgs::Float64>(boost::make_shared<std_msgs::Float64>(*zero)));
      e.run();
    };
    auto e = load(yaml, threads);
    const double exec_us = medianMicros(300, [&] { runChain(*e); });
    // The same with an observer attached: start/finish events and CPU time for every block.
    auto watched = load(yaml, threads);
    size_t events = 0;
    watched->addObserver([&events](const RunEvent&) { ++events; });
    const double watched_us = medianMicros(300, [&] { runChain(*watched); });
    const double direct_us = medianMicros(300, [&] {
      boost::shared_ptr<const std_msgs::Float64> v = boost::make_shared<std_msgs::Float64>(*zero);
      for (int i = 0; i < n; ++i) v = increment(*v);
    });
    std::printf("chain of %d trivial blocks, %d thread(s): executor %.2f us/block (with an observer: %.2f), "
                "direct calls %.3f us/block; overhead %.2f us/block (target <= %.1f)\n",
                n, threads, exec_us / n, watched_us / n, direct_us / n, (exec_us - direct_us) / n,
                threads == 1 ? 0.5 : 1.0);
    const double target = threads == 1 ? 0.5 : 1.0;
    char target_text[32];
    std::snprintf(target_text, sizeof(target_text), "<= %.1f us/block", target);
    const std::string chain = "executor, chain of 100 trivial blocks, " + std::to_string(threads) + " thread(s), us/block";
    printSummaryRow(chain + " vs direct calls", exec_us / n, direct_us / n, target_text, exec_us / n <= target);
    printSummaryRow(chain + ", with an observer vs without", watched_us / n, exec_us / n, "", false);
  }
}

// An image chain (gray -> blur -> threshold) on 1024x768, executor vs the same calls by hand.
// Both sides do the same work: read the input message's pixels in place, allocate three new
// image messages per run (newOutputImage, as the blocks do), keep the last run's three until the
// next run replaces them (the executor's output cache), all on the calling thread (OpenCV's own
// threads on both), with the same malloc settings (above).
void benchImageChain(const sensor_msgs::ImagePtr& image) {
  auto e = load(R"(
blocks:
  gray: {type: imagenets/Grayscale}
  blur: {type: imagenets/GaussianBlur, properties: {kernel_size: 5}}
  threshold: {type: imagenets/Threshold, properties: {threshold: 60}}
links: [gray.image -> blur.image, blur.image -> threshold.image]
)", 1);
  double exec_us = medianMicros(200, [&] {
    e->setInput<sensor_msgs::Image>("gray.image", image);
    e->run();
  });
  blocks::OutputImage kept[3];
  double direct_us = medianMicros(200, [&] {
    const cv::Mat in(image->height, image->width, CV_8UC3, image->data.data(), image->step);
    blocks::OutputImage g = blocks::newOutputImage(in.size(), CV_8UC1, "mono8", image->header);
    cv::cvtColor(in, g.mat, cv::COLOR_BGR2GRAY);
    blocks::OutputImage b = blocks::newOutputImage(in.size(), CV_8UC1, "mono8", image->header);
    cv::GaussianBlur(g.mat, b.mat, cv::Size(5, 5), 0);
    blocks::OutputImage t = blocks::newOutputImage(in.size(), CV_8UC1, "mono8", image->header);
    cv::threshold(b.mat, t.mat, 60, 255, cv::THRESH_BINARY);
    kept[0] = std::move(g);
    kept[1] = std::move(b);
    kept[2] = std::move(t);
  });
  std::printf("image chain gray->blur->threshold 1024x768, both sides: input read in place, 3 new image "
              "messages per run, last run's kept, freed memory kept by malloc, 1 calling thread: executor %.0f us, same calls by hand "
              "%.0f us, ratio %.2f (overhead %.1f us per block)\n",
              exec_us, direct_us, exec_us / direct_us, (exec_us - direct_us) / 3);
  printSummaryRow("executor, image chain gray->blur->threshold 1024x768, us, vs the same calls by hand", exec_us,
                  direct_us, "ratio <= 1.05", exec_us <= 1.05 * direct_us);
}

// Two independent image branches: 1 thread vs 2 threads.
void benchBranches(const sensor_msgs::ImagePtr& image) {
  const std::string yaml = R"(
blocks:
  gray: {type: imagenets/Grayscale}
  blur_a: {type: imagenets/GaussianBlur, properties: {kernel_size: 21}}
  blur_b: {type: imagenets/GaussianBlur, properties: {kernel_size: 21}}
  thr_a: {type: imagenets/Threshold}
  thr_b: {type: imagenets/Threshold}
links: [gray.image -> blur_a.image, gray.image -> blur_b.image, blur_a.image -> thr_a.image, blur_b.image -> thr_b.image]
)";
  double t[3] = {0, 0, 0};
  for (int threads : {1, 2}) {
    auto e = load(yaml, threads);
    cv::setNumThreads(1);  // measure the executor's parallelism, not OpenCV's
    t[threads] = medianMicros(60, [&] {
      e->setInput<sensor_msgs::Image>("gray.image", image);
      e->run();
    });
  }
  std::printf("two independent branches (blur 21x21 + threshold): 1 thread %.0f us, 2 threads %.0f us, "
              "speed-up %.2fx\n",
              t[1], t[2], t[1] / t[2]);
  printSummaryRow("executor, two independent branches, us, 2 threads vs 1", t[2], t[1], "", false);
}

// Feedback sweep strategies: threshold 40..80 scored by segmentation quality.
void benchFeedback(const sensor_msgs::ImagePtr& image) {
  cv::setNumThreads(1);
  std::vector<double> ms;
  for (const char* strategy : {"exhaustive, parallel: false", "exhaustive, parallel: true",
                               "coarse_to_fine, parallel: true"}) {
    auto e = load(std::string(R"(
blocks:
  gray: {type: imagenets/Grayscale}
  threshold:
    type: imagenets/Threshold
    feedback: {property: threshold, from: 40, to: 80, step: 1, score: quality.score, search: )") + strategy + R"(}
  quality: {type: imagenets/SegmentationQuality}
links: [gray.image -> threshold.image, gray.image -> quality.gray, threshold.image -> quality.binary]
)", 2);
    boost::shared_ptr<const FeedbackTrace> trace;
    double us = medianMicros(15, [&] {
      e->setInput<sensor_msgs::Image>("gray.image", image);
      e->run();
      trace = e->output<FeedbackTrace>("threshold.feedback_trace");
    });
    std::printf("feedback 40..80 (%-31s): %2u trials, %6.1f ms, chose %.0f (score %.4f)\n", strategy,
                trace->trials, us / 1000, trace->chosen_value, trace->chosen_score);
    ms.push_back(us / 1000);
  }
  printSummaryRow("feedback threshold 40..80, ms: exhaustive, trials in parallel vs one by one (2 threads)", ms[1], ms[0], "", false);
  printSummaryRow("feedback threshold 40..80, ms: coarse-to-fine vs exhaustive, both in parallel", ms[2], ms[1], "", false);
}

}  // namespace

int main(int argc, char** argv) {
  // glibc hands freed memory at the top of the heap back to the system (and faults it in again on
  // the next allocation) depending on the order of allocations, not on the work: the same three
  // 1024x768 images cost 0.4 or 1.0 ms a run by luck of layout. Keeping freed memory makes every
  // line measure its work, both sides alike.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  const std::string image_path = argc > 1 ? argv[1] : imagenets::packageFile("imagenets_blocks", "config/images/scene.png");
  cv::Mat bgr = cv::imread(image_path, cv::IMREAD_COLOR);
  if (bgr.empty()) {
    std::fprintf(stderr, "cannot read %s (run from the repository root or pass an image)\n", image_path.c_str());
    return 1;
  }
  cv::resize(bgr, bgr, cv::Size(1024, 768));
  auto image = blocks::toImageMsg(bgr, "bgr8", std_msgs::Header());

  benchTrivialChain();
  benchImageChain(image);
  benchBranches(image);
  benchFeedback(image);
  return 0;
}
