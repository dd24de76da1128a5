/*
 * FreeRTOS queue API declarations. Only TinyUSB's osal_freertos.h names them (in inline helpers
 * that the lab's usbd shim never calls), so they are declared and not defined.
 */
#ifndef SANDPAPER_LAB_QUEUE_H
#define SANDPAPER_LAB_QUEUE_H

#include "task.h"

#ifdef __cplusplus
extern "C" {
#endif

QueueHandle_t xQueueCreate(UBaseType_t length, UBaseType_t item_size);
QueueHandle_t xQueueCreateStatic(UBaseType_t length, UBaseType_t item_size, uint8_t* storage, StaticQueue_t* queue);
BaseType_t xQueueReceive(QueueHandle_t queue, void* item, TickType_t ticks_to_wait);
BaseType_t xQueueSendToBack(QueueHandle_t queue, const void* item, TickType_t ticks_to_wait);
BaseType_t xQueueSendToBackFromISR(QueueHandle_t queue, const void* item, BaseType_t* higher_priority_task_woken);
UBaseType_t uxQueueMessagesWaiting(QueueHandle_t queue);
BaseType_t xQueueReset(QueueHandle_t queue);
void vQueueDelete(QueueHandle_t queue);
void vQueueAddToRegistry(QueueHandle_t queue, const char* name);

#ifdef __cplusplus
}
#endif

#endif  // SANDPAPER_LAB_QUEUE_H
