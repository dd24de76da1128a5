// Stand-in for Firmware/FFBoard/Src/cppmain.cpp (cppmain(), the global main class and its
// chooser) and main.c's default task. cppmain.cpp is not compiled because it replaces malloc and
// free with the RTOS heap for the whole process and checks the chip's ID and the failsafe button
// through raw registers. The steps below are cppmain()'s, in its order (cppmain.cpp lines 31-109
// at the firmware's commit), minus the device-ID check and the failsafe button (BTNFAILSAFE is not
// defined for the lab target).
#include "startup.hpp"

#include <atomic>

#include "ClassChooser.h"
#include "PersistentStorage.h"
#include "FreeRTOS.h"
#include "cppmain.h"
#include "flash_helpers.h"
#include "global_callbacks.h"
#include "ledEffects.h"
#include "mainclass_chooser.h"
#include "task.h"

// cppmain.cpp's globals, under the same names (global_callbacks.cpp and SystemCommands.cpp use
// mainclass).
bool running = true;
bool mainclassChosen = false;
volatile bool forceErase = false;
uint16_t main_id = 0;
FFBoardMain* mainclass = nullptr;
ClassChooser<FFBoardMain> mainchooser(class_registry);
void* defaultTaskHandle = nullptr;  // main.c's osThreadId_t

namespace sandpaper::usb_lab::startup {
namespace {

std::atomic<bool> ready{false};

void cppmain_steps() {
  if (!Flash_Init()) Error_Handler();
  if (forceErase) {
    Flash_Format();
    Flash_Write_Defaults();
  }
  // Check if flash is initialized
  uint16_t lastFlashVersion = 0;
  if (!Flash_Read(ADR_FLASH_VERSION, &lastFlashVersion)) {  // Version never written
    Flash_Write_Defaults();
    Flash_Write(ADR_FLASH_VERSION, FLASH_VERSION);
  }
  Flash_Read(ADR_FLASH_VERSION, &lastFlashVersion);
  if (lastFlashVersion != FLASH_VERSION) {
    Flash_Format();
    Flash_Write_Defaults();
    Flash_Write(ADR_FLASH_VERSION, FLASH_VERSION);
  }

  startADC();

  if (!Flash_ReadWriteDefault(ADR_CURRENT_CONFIG, &main_id, DEFAULTMAIN)) {
    Error_Handler();  // the default was written (first start); the board's handler only sets an LED
  }

  PersistentStorage::restoreFlashStartupCb();

  mainclass = mainchooser.Create(main_id);
  if (mainclass == nullptr) mainclass = mainchooser.Create(0);
  mainclassChosen = true;

  mainclass->usbInit();
  ready = true;

  while (running) {
    mainclass->update();
    updateLeds();
    refreshWatchdog();
    taskYIELD();
  }
}

// main.c StartDefaultTask: LEDs off, then cppmain() forever.
void default_task(void*) {
  HAL_GPIO_WritePin(LED_ERR_GPIO_Port, LED_ERR_Pin, GPIO_PIN_RESET);
  HAL_GPIO_WritePin(LED_CLIP_GPIO_Port, LED_CLIP_Pin, GPIO_PIN_RESET);
  HAL_GPIO_WritePin(LED_SYS_GPIO_Port, LED_SYS_Pin, GPIO_PIN_RESET);
  for (;;) cppmain_steps();
}

}  // namespace

void start_default_task() {
  TaskHandle_t handle = nullptr;
  // main.c: defaultTask, osPriorityNormal (24), stack 512 words.
  xTaskCreate(default_task, "defaultTask", 512, nullptr, 24, &handle);
  defaultTaskHandle = handle;
}

bool main_class_ready() { return ready.load(); }

}  // namespace sandpaper::usb_lab::startup
