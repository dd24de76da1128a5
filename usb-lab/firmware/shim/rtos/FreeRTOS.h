/*
 * FreeRTOS kernel types and configuration for the OpenFFBoard firmware on the host.
 *
 * The firmware's own cpp_freertos wrappers (thread.hpp, semaphore.hpp, mutex.hpp, cthread.cpp ...)
 * are compiled as they are on top of this kernel API; rtos_kernel.cpp implements it with
 * std::thread and steady-clock time. Configuration is the F407VG target's FreeRTOSConfig.h
 * (1 ms ticks, 56 priorities).
 */
#ifndef SANDPAPER_LAB_FREERTOS_H
#define SANDPAPER_LAB_FREERTOS_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#include "FreeRTOSConfig.h"

// Defaults the kernel's FreeRTOS.h gives options the target's FreeRTOSConfig.h leaves unset.
#ifndef configUSE_TASK_NOTIFICATIONS
#define configUSE_TASK_NOTIFICATIONS 1
#endif
#ifndef INCLUDE_xTaskResumeFromISR
#define INCLUDE_xTaskResumeFromISR 1
#endif

typedef long BaseType_t;
typedef unsigned long UBaseType_t;
typedef uint32_t TickType_t;
typedef uint32_t StackType_t;
typedef struct LabTask* TaskHandle_t;
typedef struct LabQueue* QueueHandle_t;
typedef void (*TaskFunction_t)(void*);

// Storage types of the static-allocation API (TinyUSB's osal_freertos.h names them).
typedef struct { void* reserved[16]; } StaticTask_t;
typedef struct { void* reserved[16]; } StaticQueue_t;
typedef StaticQueue_t StaticSemaphore_t;

#define pdFALSE ((BaseType_t)0)
#define pdTRUE ((BaseType_t)1)
#define pdPASS (pdTRUE)
#define pdFAIL (pdFALSE)
#define errQUEUE_EMPTY ((BaseType_t)0)
#define errQUEUE_FULL ((BaseType_t)0)
#define portMAX_DELAY ((TickType_t)0xffffffffUL)
#define portTICK_PERIOD_MS ((TickType_t)1000 / configTICK_RATE_HZ)
#define portTICK_RATE_MS portTICK_PERIOD_MS
#define pdMS_TO_TICKS(xTimeInMs) \
  ((TickType_t)(((TickType_t)(xTimeInMs) * (TickType_t)configTICK_RATE_HZ) / (TickType_t)1000U))
#define portYIELD_FROM_ISR(x) ((void)(x))
#define portEND_SWITCHING_ISR(x) ((void)(x))
#define configSTACK_DEPTH_TYPE uint16_t

size_t xPortGetFreeHeapSize(void);
size_t xPortGetMinimumEverFreeHeapSize(void);
void* pvPortMalloc(size_t size);
void vPortFree(void* p);

#ifdef __cplusplus
}
#endif

#endif  // SANDPAPER_LAB_FREERTOS_H
