// The FreeRTOS kernel API the OpenFFBoard firmware and its cpp_freertos wrappers call, on the host:
// tasks are std::threads on the emulated core (lab_core.hpp), time is the steady clock in 1 ms
// ticks, notifications and semaphores are counters with a condition variable.
#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "FreeRTOS.h"
#include "lab_core.hpp"
#include "semphr.h"
#include "task.h"
#include "task_hooks.hpp"

namespace core = sandpaper::usb_lab::core;

struct LabTask {
  std::string name;
  UBaseType_t priority = 0;
  std::mutex mutex;
  std::condition_variable wake;
  std::uint32_t notification = 0;
  bool suspended = false;
  std::atomic<bool> deleted{false};
};

enum class SemKind { binary, counting, mutex, recursive_mutex };

struct LabQueue {  // FreeRTOS semaphores are queues; only the semaphore kinds exist here
  SemKind kind = SemKind::binary;
  std::mutex mutex;
  std::condition_variable given;
  UBaseType_t count = 0;
  UBaseType_t max_count = 1;
  std::thread::id holder;  // mutexes: the thread that took it
  UBaseType_t recursion = 0;
};

namespace {

thread_local LabTask* current_task = nullptr;

std::vector<LabTask*>& task_list() {
  static auto* tasks = new std::vector<LabTask*>();  // never destroyed (threads outlive statics)
  return *tasks;
}

std::mutex& task_list_mutex() {
  static auto* m = new std::mutex();
  return *m;
}

// Read and written holding the core.
std::function<void(std::string_view)>& after_notification_take() {
  static auto* f = new std::function<void(std::string_view)>();  // never destroyed (threads outlive statics)
  return *f;
}

// The deadline of a wait of `ticks` RTOS ticks starting now, or none for portMAX_DELAY.
std::optional<core::Clock::time_point> deadline_after(TickType_t ticks) {
  if (ticks == portMAX_DELAY) return std::nullopt;
  return core::tick_time(static_cast<unsigned long long>(xTaskGetTickCount()) + ticks);
}

// A task deleted by another while it waited must not run again: it parks.
void stop_if_deleted() {
  if (current_task != nullptr && current_task->deleted.load()) {
    core::release();
    core::park_forever();
  }
}

// Blocks the calling task in `wait` with the emulated core given up meanwhile.
void block(const std::function<void()>& wait) {
  core::wait_released(wait);
  stop_if_deleted();
}

// Waits on `cv` until `ready` or the deadline, with the emulated core given up meanwhile. `lock`
// (the object's own mutex) is never held while the core is being taken back: whoever holds the
// core may need it to give or notify. So `ready` is checked again once both are held, and the
// wait goes on if another task got there first.
template <class Ready>
bool wait_for(std::unique_lock<std::mutex>& lock, std::condition_variable& cv, TickType_t ticks, Ready ready) {
  const auto deadline = deadline_after(ticks);
  for (;;) {
    if (ready()) return true;
    if (ticks == 0 || (deadline && core::Clock::now() >= *deadline)) return false;
    block([&] {
      if (deadline) {
        cv.wait_until(lock, *deadline, ready);
      } else {
        cv.wait(lock, ready);
      }
      lock.unlock();
    });
    lock.lock();
  }
}

void task_entry(LabTask* task, TaskFunction_t fn, void* param) {
  current_task = task;
  core::acquire();
  fn(param);
  vTaskDelete(nullptr);
}

}  // namespace

extern "C" {

BaseType_t xTaskCreate(TaskFunction_t fn, const char* name, configSTACK_DEPTH_TYPE, void* param,
                       UBaseType_t priority, TaskHandle_t* created) {
  auto* task = new LabTask();
  task->name = name ? name : "";
  task->priority = priority;
  {
    std::lock_guard lock(task_list_mutex());
    task_list().push_back(task);
  }
  if (created) *created = task;
  std::thread(task_entry, task, fn, param).detach();
  return pdPASS;
}

// A task cannot be stopped from outside on the host; a deleted task stops at its next wait
// (it parks there forever). Deleting the calling task parks it now.
void vTaskDelete(TaskHandle_t task) {
  if (task == nullptr || task == current_task) {
    core::release();
    core::park_forever();
  }
  task->deleted = true;
  std::lock_guard lock(task_list_mutex());
  auto& tasks = task_list();
  tasks.erase(std::remove(tasks.begin(), tasks.end(), task), tasks.end());
}

TickType_t xTaskGetTickCount(void) {
  const auto since = core::Clock::now() - core::epoch();
  return static_cast<TickType_t>(std::chrono::duration_cast<std::chrono::milliseconds>(since).count());
}

TickType_t xTaskGetTickCountFromISR(void) { return xTaskGetTickCount(); }
TaskHandle_t xTaskGetCurrentTaskHandle(void) { return current_task; }

// Until the tick `ticks` after the current one, as the kernel's tick-driven delay list wakes it.
void vTaskDelay(TickType_t ticks) {
  if (ticks == 0) {
    lab_task_yield();
    return;
  }
  const auto until = core::tick_time(static_cast<unsigned long long>(xTaskGetTickCount()) + ticks);
  block([&] { std::this_thread::sleep_until(until); });
}

void vTaskDelayUntil(TickType_t* previous_wake, TickType_t increment) {
  *previous_wake += increment;
  const auto until = core::tick_time(*previous_wake);
  block([&] { std::this_thread::sleep_until(until); });
}

BaseType_t xTaskNotifyGive(TaskHandle_t task) {
  {
    std::lock_guard lock(task->mutex);
    ++task->notification;
  }
  task->wake.notify_all();
  return pdPASS;
}

void vTaskNotifyGiveFromISR(TaskHandle_t task, BaseType_t* higher_priority_task_woken) {
  xTaskNotifyGive(task);
  if (higher_priority_task_woken) *higher_priority_task_woken = pdTRUE;
}

uint32_t ulTaskNotifyTake(BaseType_t clear_on_exit, TickType_t ticks_to_wait) {
  LabTask* task = current_task;
  if (task == nullptr) return 0;
  std::unique_lock lock(task->mutex);
  if (!wait_for(lock, task->wake, ticks_to_wait, [&] { return task->notification > 0; })) return 0;
  const std::uint32_t value = task->notification;
  task->notification = clear_on_exit ? 0 : value - 1;
  lock.unlock();
  if (const auto& hook = after_notification_take()) hook(task->name);
  return value;
}

void vTaskSuspend(TaskHandle_t task) {
  LabTask* t = task ? task : current_task;
  if (t == nullptr) return;
  std::unique_lock lock(t->mutex);
  t->suspended = true;
  if (t == current_task) wait_for(lock, t->wake, portMAX_DELAY, [&] { return !t->suspended; });
}

void vTaskResume(TaskHandle_t task) {
  {
    std::lock_guard lock(task->mutex);
    task->suspended = false;
  }
  task->wake.notify_all();
}

BaseType_t xTaskResumeFromISR(TaskHandle_t task) {
  vTaskResume(task);
  return pdTRUE;
}

void vTaskPrioritySet(TaskHandle_t task, UBaseType_t priority) {
  LabTask* t = task ? task : current_task;
  if (t) t->priority = priority;
}

UBaseType_t uxTaskPriorityGet(TaskHandle_t task) {
  LabTask* t = task ? task : current_task;
  return t ? t->priority : 0;
}

UBaseType_t uxTaskPriorityGetFromISR(TaskHandle_t task) { return uxTaskPriorityGet(task); }

char* pcTaskGetName(TaskHandle_t task) {
  LabTask* t = task ? task : current_task;
  static char none[] = "";
  return t ? t->name.data() : none;
}

UBaseType_t uxTaskGetNumberOfTasks(void) {
  std::lock_guard lock(task_list_mutex());
  return task_list().size();
}

void vTaskList(char* buffer) {
  std::string out;
  std::lock_guard lock(task_list_mutex());
  for (const LabTask* t : task_list()) out += t->name + "\tR\t" + std::to_string(t->priority) + "\t0\t0\r\n";
  std::memcpy(buffer, out.c_str(), out.size() + 1);
}

void vTaskGetRunTimeStats(char* buffer) { std::strcpy(buffer, "(no run time statistics on the host)\r\n"); }

void vTaskStartScheduler(void) {}
void vTaskEndScheduler(void) {}
void vTaskSuspendAll(void) {}  // one task runs at a time already (lab_core.hpp)
BaseType_t xTaskResumeAll(void) { return pdFALSE; }

void lab_task_yield(void) {
  block([] { std::this_thread::yield(); });
}

// ---- Semaphores and mutexes

static SemaphoreHandle_t make_semaphore(SemKind kind, UBaseType_t max_count, UBaseType_t initial) {
  auto* sem = new LabQueue();
  sem->kind = kind;
  sem->max_count = max_count;
  sem->count = initial;
  return sem;
}

SemaphoreHandle_t xSemaphoreCreateBinary(void) { return make_semaphore(SemKind::binary, 1, 0); }
SemaphoreHandle_t xSemaphoreCreateCounting(UBaseType_t max_count, UBaseType_t initial_count) {
  return make_semaphore(SemKind::counting, max_count, initial_count);
}
SemaphoreHandle_t xSemaphoreCreateMutex(void) { return make_semaphore(SemKind::mutex, 1, 1); }
SemaphoreHandle_t xSemaphoreCreateRecursiveMutex(void) { return make_semaphore(SemKind::recursive_mutex, 1, 1); }
SemaphoreHandle_t xSemaphoreCreateBinaryStatic(StaticSemaphore_t*) { return xSemaphoreCreateBinary(); }
SemaphoreHandle_t xSemaphoreCreateMutexStatic(StaticSemaphore_t*) { return xSemaphoreCreateMutex(); }

BaseType_t xSemaphoreTake(SemaphoreHandle_t sem, TickType_t ticks_to_wait) {
  std::unique_lock lock(sem->mutex);
  if (!wait_for(lock, sem->given, ticks_to_wait, [&] { return sem->count > 0; })) return pdFALSE;
  --sem->count;
  sem->holder = std::this_thread::get_id();
  return pdTRUE;
}

BaseType_t xSemaphoreGive(SemaphoreHandle_t sem) {
  {
    std::lock_guard lock(sem->mutex);
    if (sem->count >= sem->max_count) return pdFALSE;
    ++sem->count;
    sem->holder = std::thread::id();
  }
  sem->given.notify_all();
  return pdTRUE;
}

BaseType_t xSemaphoreTakeRecursive(SemaphoreHandle_t sem, TickType_t ticks_to_wait) {
  {
    std::lock_guard lock(sem->mutex);
    if (sem->recursion > 0 && sem->holder == std::this_thread::get_id()) {
      ++sem->recursion;
      return pdTRUE;
    }
  }
  if (xSemaphoreTake(sem, ticks_to_wait) != pdTRUE) return pdFALSE;
  std::lock_guard lock(sem->mutex);
  sem->recursion = 1;
  return pdTRUE;
}

BaseType_t xSemaphoreGiveRecursive(SemaphoreHandle_t sem) {
  {
    std::lock_guard lock(sem->mutex);
    if (sem->recursion == 0 || sem->holder != std::this_thread::get_id()) return pdFALSE;
    if (--sem->recursion > 0) return pdTRUE;
  }
  return xSemaphoreGive(sem);
}

BaseType_t xSemaphoreTakeFromISR(SemaphoreHandle_t sem, BaseType_t* higher_priority_task_woken) {
  if (higher_priority_task_woken) *higher_priority_task_woken = pdFALSE;
  return xSemaphoreTake(sem, 0);
}

BaseType_t xSemaphoreGiveFromISR(SemaphoreHandle_t sem, BaseType_t* higher_priority_task_woken) {
  if (higher_priority_task_woken) *higher_priority_task_woken = pdTRUE;
  return xSemaphoreGive(sem);
}

UBaseType_t uxSemaphoreGetCount(SemaphoreHandle_t sem) {
  std::lock_guard lock(sem->mutex);
  return sem->count;
}

// Never freed: a task parked after halt() may still hold a reference.
void vSemaphoreDelete(SemaphoreHandle_t) {}

// ---- Heap figures SystemCommands reports (the host heap has no fixed size).
size_t xPortGetFreeHeapSize(void) { return configTOTAL_HEAP_SIZE; }
size_t xPortGetMinimumEverFreeHeapSize(void) { return configTOTAL_HEAP_SIZE; }
void* pvPortMalloc(size_t size) { return std::malloc(size); }
void vPortFree(void* p) { std::free(p); }

}  // extern "C"

namespace sandpaper::usb_lab::rtos {
void set_after_notification_take(std::function<void(std::string_view)> hook) { after_notification_take() = std::move(hook); }
}  // namespace sandpaper::usb_lab::rtos
