/*
 * FreeRTOS semaphore and mutex API for the OpenFFBoard firmware on the host (rtos_kernel.cpp).
 * A wait gives the emulated core to the other tasks until the semaphore is given or time is up.
 */
#ifndef SANDPAPER_LAB_SEMPHR_H
#define SANDPAPER_LAB_SEMPHR_H

#include "queue.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef QueueHandle_t SemaphoreHandle_t;

SemaphoreHandle_t xSemaphoreCreateBinary(void);
SemaphoreHandle_t xSemaphoreCreateCounting(UBaseType_t max_count, UBaseType_t initial_count);
SemaphoreHandle_t xSemaphoreCreateMutex(void);
SemaphoreHandle_t xSemaphoreCreateRecursiveMutex(void);
SemaphoreHandle_t xSemaphoreCreateBinaryStatic(StaticSemaphore_t* storage);
SemaphoreHandle_t xSemaphoreCreateMutexStatic(StaticSemaphore_t* storage);
BaseType_t xSemaphoreTake(SemaphoreHandle_t sem, TickType_t ticks_to_wait);
BaseType_t xSemaphoreGive(SemaphoreHandle_t sem);
BaseType_t xSemaphoreTakeRecursive(SemaphoreHandle_t sem, TickType_t ticks_to_wait);
BaseType_t xSemaphoreGiveRecursive(SemaphoreHandle_t sem);
BaseType_t xSemaphoreTakeFromISR(SemaphoreHandle_t sem, BaseType_t* higher_priority_task_woken);
BaseType_t xSemaphoreGiveFromISR(SemaphoreHandle_t sem, BaseType_t* higher_priority_task_woken);
UBaseType_t uxSemaphoreGetCount(SemaphoreHandle_t sem);
void vSemaphoreDelete(SemaphoreHandle_t sem);

#ifdef __cplusplus
}
#endif

#endif  // SANDPAPER_LAB_SEMPHR_H
