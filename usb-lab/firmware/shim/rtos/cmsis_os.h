/*
 * CMSIS-RTOS2 names the OpenFFBoard firmware's files use (an extern thread handle); the kernel
 * API itself is FreeRTOS's (task.h).
 */
#ifndef SANDPAPER_LAB_CMSIS_OS_H
#define SANDPAPER_LAB_CMSIS_OS_H

#include "FreeRTOS.h"
#include "task.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef void* osThreadId_t;
typedef osThreadId_t osThreadId;

#ifdef __cplusplus
}
#endif

#endif  // SANDPAPER_LAB_CMSIS_OS_H
