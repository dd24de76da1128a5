/*
 * FreeRTOS task API for the OpenFFBoard firmware on the host (rtos_kernel.cpp).
 *
 * Tasks are std::threads that take turns on one emulated core: a task runs until it blocks
 * (delay, notification wait, semaphore wait) or yields, so firmware code never runs in two
 * threads at once, as on the single-core STM32. Priorities are kept but do not preempt.
 * Critical sections and scheduler suspension need no lock under that rule and do nothing.
 */
#ifndef SANDPAPER_LAB_TASK_H
#define SANDPAPER_LAB_TASK_H

#include "FreeRTOS.h"

#ifdef __cplusplus
extern "C" {
#endif

BaseType_t xTaskCreate(TaskFunction_t fn, const char* name, configSTACK_DEPTH_TYPE stack_depth, void* param,
                       UBaseType_t priority, TaskHandle_t* created);
void vTaskDelete(TaskHandle_t task);
void vTaskDelay(TickType_t ticks);
void vTaskDelayUntil(TickType_t* previous_wake, TickType_t increment);
TickType_t xTaskGetTickCount(void);
TickType_t xTaskGetTickCountFromISR(void);
TaskHandle_t xTaskGetCurrentTaskHandle(void);

BaseType_t xTaskNotifyGive(TaskHandle_t task);
void vTaskNotifyGiveFromISR(TaskHandle_t task, BaseType_t* higher_priority_task_woken);
uint32_t ulTaskNotifyTake(BaseType_t clear_on_exit, TickType_t ticks_to_wait);

void vTaskSuspend(TaskHandle_t task);
void vTaskResume(TaskHandle_t task);
BaseType_t xTaskResumeFromISR(TaskHandle_t task);
void vTaskPrioritySet(TaskHandle_t task, UBaseType_t priority);
UBaseType_t uxTaskPriorityGet(TaskHandle_t task);
UBaseType_t uxTaskPriorityGetFromISR(TaskHandle_t task);
char* pcTaskGetName(TaskHandle_t task);
UBaseType_t uxTaskGetNumberOfTasks(void);
void vTaskList(char* buffer);
void vTaskGetRunTimeStats(char* buffer);

void vTaskStartScheduler(void);
void vTaskEndScheduler(void);
void vTaskSuspendAll(void);
BaseType_t xTaskResumeAll(void);
void lab_task_yield(void);

#define taskYIELD() lab_task_yield()
#define taskENTER_CRITICAL() ((void)0)
#define taskEXIT_CRITICAL() ((void)0)
#define taskENTER_CRITICAL_FROM_ISR() ((BaseType_t)0)
#define taskEXIT_CRITICAL_FROM_ISR(x) ((void)(x))
#define taskDISABLE_INTERRUPTS() ((void)0)
#define taskENABLE_INTERRUPTS() ((void)0)

#ifdef __cplusplus
}
#endif

#endif  // SANDPAPER_LAB_TASK_H
