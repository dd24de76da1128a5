// The STM32F4 HAL functions the OpenFFBoard firmware calls, for the host (stm32f4xx_hal.h says
// what each does). Peripheral handles are defined here as the F407VG's main.c defines them.
#include <chrono>

#include "lab_core.hpp"
#include "main.h"  // the F407VG's pin names
#include "stm32f4xx_hal.h"

namespace core = sandpaper::usb_lab::core;

extern "C" {

uint32_t SystemCoreClock = 168000000u;

UART_HandleTypeDef huart1 = {};
ADC_HandleTypeDef hadc1 = {};
ADC_HandleTypeDef hadc2 = {};

// lab_gpio_ports' ODR holds what the firmware wrote.
GPIO_TypeDef lab_gpio_ports[9] = {};

// An input nobody drives reads its pull: main.c MX_GPIO_Init pulls the digital inputs DIN0-7 and
// the E-stop up (released), the rest down or floating (read low).
static bool pulled_up(const GPIO_TypeDef* port, uint16_t pin) {
  if (port == E_STOP_GPIO_Port && (pin & E_STOP_Pin)) return true;
  if (port == DIN3_GPIO_Port && (pin & (DIN7_Pin | DIN6_Pin | DIN5_Pin | DIN4_Pin | DIN3_Pin))) return true;
  if (port == DIN0_GPIO_Port && (pin & (DIN2_Pin | DIN1_Pin | DIN0_Pin))) return true;
  return false;
}

uint32_t HAL_GetTick(void) {
  const auto since = core::Clock::now() - core::epoch();
  return static_cast<uint32_t>(std::chrono::duration_cast<std::chrono::milliseconds>(since).count());
}

uint32_t HAL_RCC_GetHCLKFreq(void) { return SystemCoreClock; }
uint32_t HAL_GetDEVID(void) { return 0x413u; }  // STM32F405/407 (the target's FW_DEVID)
uint32_t HAL_GetREVID(void) { return 0x1007u; }
// A fixed unique ID; the USB serial number is its words in hex, word 2 first.
uint32_t HAL_GetUIDw0(void) { return 0x004c0036u; }
uint32_t HAL_GetUIDw1(void) { return 0x4d4e5001u; }
uint32_t HAL_GetUIDw2(void) { return 0x20353433u; }
void HAL_NVIC_SystemReset(void) {}
void NVIC_SystemReset(void) {}

void HAL_GPIO_Init(GPIO_TypeDef*, GPIO_InitTypeDef*) {}

// Outputs read back what was written; inputs read their pull.
GPIO_PinState HAL_GPIO_ReadPin(GPIO_TypeDef* port, uint16_t pin) {
  return (port->ODR & pin) != 0 || pulled_up(port, pin) ? GPIO_PIN_SET : GPIO_PIN_RESET;
}

void HAL_GPIO_WritePin(GPIO_TypeDef* port, uint16_t pin, GPIO_PinState state) {
  if (state == GPIO_PIN_SET) {
    port->ODR |= pin;
  } else {
    port->ODR &= ~static_cast<uint32_t>(pin);
  }
}

void HAL_GPIO_TogglePin(GPIO_TypeDef* port, uint16_t pin) { port->ODR ^= pin; }

HAL_StatusTypeDef HAL_UART_Init(UART_HandleTypeDef*) { return HAL_OK; }
HAL_StatusTypeDef HAL_UART_Transmit(UART_HandleTypeDef*, const uint8_t*, uint16_t, uint32_t) { return HAL_ERROR; }
HAL_StatusTypeDef HAL_UART_Receive(UART_HandleTypeDef*, uint8_t*, uint16_t, uint32_t) { return HAL_ERROR; }
HAL_StatusTypeDef HAL_UART_Transmit_IT(UART_HandleTypeDef*, const uint8_t*, uint16_t) { return HAL_ERROR; }
HAL_StatusTypeDef HAL_UART_Receive_IT(UART_HandleTypeDef*, uint8_t*, uint16_t) { return HAL_ERROR; }
HAL_StatusTypeDef HAL_UART_Transmit_DMA(UART_HandleTypeDef*, const uint8_t*, uint16_t) { return HAL_ERROR; }
HAL_StatusTypeDef HAL_UART_Receive_DMA(UART_HandleTypeDef*, uint8_t*, uint16_t) { return HAL_ERROR; }
HAL_StatusTypeDef HAL_UART_AbortReceive(UART_HandleTypeDef*) { return HAL_OK; }
HAL_StatusTypeDef HAL_UART_AbortTransmit(UART_HandleTypeDef*) { return HAL_OK; }

HAL_StatusTypeDef HAL_ADC_Start_DMA(ADC_HandleTypeDef*, uint32_t*, uint32_t) { return HAL_OK; }

HAL_StatusTypeDef HAL_FLASH_Unlock(void) { return HAL_OK; }
HAL_StatusTypeDef HAL_FLASH_Lock(void) { return HAL_OK; }

// What main.c provides besides its HAL init code.
void Error_Handler(void) {}
void RebootDFU(void) {}
void ExitDFU(void) {}

}  // extern "C"
