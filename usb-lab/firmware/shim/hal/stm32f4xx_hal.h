/*
 * The part of the STM32F4 HAL the OpenFFBoard firmware's compiled files name, for the host.
 *
 * Types are plain structs with the fields the firmware reads or writes; functions do nothing and
 * report success unless the lab needs them to act (ticks, the TIM_FFB update interrupt, the chip's
 * identity). Definitions: hal_shim.cpp. Values follow the F407VG target (main.c at the firmware's
 * commit: SYSCLK 168 MHz, TIM13 on the 84 MHz APB1 timer clock, prescaler 84-1).
 */
#ifndef SANDPAPER_LAB_STM32F4XX_HAL_H
#define SANDPAPER_LAB_STM32F4XX_HAL_H

#include <stddef.h>
#include <stdint.h>

#include "cmsis_compiler.h"

#ifdef __cplusplus
extern "C" {
#endif

#define __IO volatile
// stm32f4xx_hal_def.h: alignment of USB descriptor arrays.
#define __ALIGN_BEGIN
#define __ALIGN_END __attribute__((aligned(4)))
#define ENABLE 1
#define DISABLE 0

typedef enum { HAL_OK = 0x00, HAL_ERROR = 0x01, HAL_BUSY = 0x02, HAL_TIMEOUT = 0x03 } HAL_StatusTypeDef;

extern uint32_t SystemCoreClock;  // 168 MHz, as the F407VG's clock tree sets it
uint32_t HAL_GetTick(void);       // milliseconds since the firmware started (steady clock)
uint32_t HAL_RCC_GetHCLKFreq(void);
uint32_t HAL_GetDEVID(void);      // FW_DEVID: the firmware's chip check passes
uint32_t HAL_GetREVID(void);
uint32_t HAL_GetUIDw0(void);      // the chip's unique ID: fixed words, the USB serial is made of them
uint32_t HAL_GetUIDw1(void);
uint32_t HAL_GetUIDw2(void);
void HAL_NVIC_SystemReset(void);
void NVIC_SystemReset(void);

// ---- GPIO: writes are kept; a read gives the pin's written level, or for an undriven input its
// pull as the F407VG's main.c sets it (E-stop and digital inputs pulled up: released).
typedef struct {
  uint32_t ODR;
} GPIO_TypeDef;
extern GPIO_TypeDef lab_gpio_ports[9];
#define GPIOA (&lab_gpio_ports[0])
#define GPIOB (&lab_gpio_ports[1])
#define GPIOC (&lab_gpio_ports[2])
#define GPIOD (&lab_gpio_ports[3])
#define GPIOE (&lab_gpio_ports[4])
#define GPIOF (&lab_gpio_ports[5])
#define GPIOG (&lab_gpio_ports[6])
#define GPIOH (&lab_gpio_ports[7])
#define GPIOI (&lab_gpio_ports[8])

typedef enum { GPIO_PIN_RESET = 0, GPIO_PIN_SET } GPIO_PinState;
#define GPIO_PIN_0 ((uint16_t)0x0001)
#define GPIO_PIN_1 ((uint16_t)0x0002)
#define GPIO_PIN_2 ((uint16_t)0x0004)
#define GPIO_PIN_3 ((uint16_t)0x0008)
#define GPIO_PIN_4 ((uint16_t)0x0010)
#define GPIO_PIN_5 ((uint16_t)0x0020)
#define GPIO_PIN_6 ((uint16_t)0x0040)
#define GPIO_PIN_7 ((uint16_t)0x0080)
#define GPIO_PIN_8 ((uint16_t)0x0100)
#define GPIO_PIN_9 ((uint16_t)0x0200)
#define GPIO_PIN_10 ((uint16_t)0x0400)
#define GPIO_PIN_11 ((uint16_t)0x0800)
#define GPIO_PIN_12 ((uint16_t)0x1000)
#define GPIO_PIN_13 ((uint16_t)0x2000)
#define GPIO_PIN_14 ((uint16_t)0x4000)
#define GPIO_PIN_15 ((uint16_t)0x8000)

typedef struct {
  uint32_t Pin, Mode, Pull, Speed, Alternate;
} GPIO_InitTypeDef;
#define GPIO_MODE_INPUT 0x0u
#define GPIO_MODE_OUTPUT_PP 0x1u
#define GPIO_MODE_OUTPUT_OD 0x11u
#define GPIO_NOPULL 0x0u
#define GPIO_PULLUP 0x1u
#define GPIO_PULLDOWN 0x2u
#define GPIO_SPEED_FREQ_LOW 0x0u
#define GPIO_SPEED_FREQ_MEDIUM 0x1u
#define GPIO_SPEED_FREQ_HIGH 0x2u
#define GPIO_SPEED_FREQ_VERY_HIGH 0x3u

void HAL_GPIO_Init(GPIO_TypeDef* port, GPIO_InitTypeDef* init);
GPIO_PinState HAL_GPIO_ReadPin(GPIO_TypeDef* port, uint16_t pin);
void HAL_GPIO_WritePin(GPIO_TypeDef* port, uint16_t pin, GPIO_PinState state);
void HAL_GPIO_TogglePin(GPIO_TypeDef* port, uint16_t pin);

// IRQ numbers main.h names for its EXTI pins.
typedef enum { EXTI2_IRQn = 8, EXTI9_5_IRQn = 23, EXTI15_10_IRQn = 40 } IRQn_Type;

// ---- Timers: registers in timer-clock steps. HAL_TIM_Base_Start_IT starts the update interrupt:
// HAL_TIM_PeriodElapsedCallback every (PSC+1)*(ARR+1) timer-clock cycles (hal_timer.cpp).
typedef struct {
  volatile uint32_t CNT, PSC, ARR;
} TIM_TypeDef;
typedef struct {
  uint32_t Prescaler, CounterMode, Period, ClockDivision, AutoReloadPreload;
} TIM_Base_InitTypeDef;
typedef struct {
  TIM_TypeDef* Instance;
  TIM_Base_InitTypeDef Init;
} TIM_HandleTypeDef;
#define TIM_CHANNEL_1 0x00000000u
#define TIM_CHANNEL_2 0x00000004u
#define TIM_CHANNEL_3 0x00000008u
#define TIM_CHANNEL_4 0x0000000Cu
extern TIM_HandleTypeDef htim13;  // TIM_FFB on the F407VG
extern TIM_HandleTypeDef htim9;   // TIM_USER
HAL_StatusTypeDef HAL_TIM_Base_Start_IT(TIM_HandleTypeDef* htim);
HAL_StatusTypeDef HAL_TIM_Base_Stop_IT(TIM_HandleTypeDef* htim);
void HAL_TIM_PeriodElapsedCallback(TIM_HandleTypeDef* htim);  // the firmware's (global_callbacks.cpp)

// ---- Peripherals the firmware's headers name; no hardware behind them.
typedef struct {
  uint32_t BaudRate, WordLength, StopBits, Parity, Mode, HwFlowCtl, OverSampling;
} UART_InitTypeDef;
typedef struct {
  void* Instance;
  UART_InitTypeDef Init;
  uint32_t ErrorCode;
} UART_HandleTypeDef;
extern UART_HandleTypeDef huart1;
HAL_StatusTypeDef HAL_UART_Init(UART_HandleTypeDef* huart);
HAL_StatusTypeDef HAL_UART_Transmit(UART_HandleTypeDef* huart, const uint8_t* data, uint16_t size, uint32_t timeout);
HAL_StatusTypeDef HAL_UART_Receive(UART_HandleTypeDef* huart, uint8_t* data, uint16_t size, uint32_t timeout);
HAL_StatusTypeDef HAL_UART_Transmit_IT(UART_HandleTypeDef* huart, const uint8_t* data, uint16_t size);
HAL_StatusTypeDef HAL_UART_Receive_IT(UART_HandleTypeDef* huart, uint8_t* data, uint16_t size);
HAL_StatusTypeDef HAL_UART_Transmit_DMA(UART_HandleTypeDef* huart, const uint8_t* data, uint16_t size);
HAL_StatusTypeDef HAL_UART_Receive_DMA(UART_HandleTypeDef* huart, uint8_t* data, uint16_t size);
HAL_StatusTypeDef HAL_UART_AbortReceive(UART_HandleTypeDef* huart);
HAL_StatusTypeDef HAL_UART_AbortTransmit(UART_HandleTypeDef* huart);
void HAL_UART_RxCpltCallback(UART_HandleTypeDef* huart);
void HAL_UART_TxCpltCallback(UART_HandleTypeDef* huart);

typedef struct {
  uint32_t Mode, Direction, DataSize, CLKPolarity, CLKPhase, NSS, BaudRatePrescaler, FirstBit, TIMode,
      CRCCalculation, CRCPolynomial;
} SPI_InitTypeDef;
typedef struct {
  void* Instance;
  SPI_InitTypeDef Init;
} SPI_HandleTypeDef;
#define SPI_MODE_MASTER 0x0104u
#define SPI_DIRECTION_2LINES 0x0000u
#define SPI_DATASIZE_8BIT 0x0000u
#define SPI_POLARITY_LOW 0x0000u
#define SPI_PHASE_1EDGE 0x0000u
#define SPI_NSS_SOFT 0x0200u
#define SPI_BAUDRATEPRESCALER_4 0x0008u
#define SPI_BAUDRATEPRESCALER_16 0x0018u
#define SPI_BAUDRATEPRESCALER_32 0x0020u
#define SPI_BAUDRATEPRESCALER_64 0x0028u
#define SPI_FIRSTBIT_MSB 0x0000u
#define SPI_TIMODE_DISABLE 0x0000u
#define SPI_CRCCALCULATION_DISABLE 0x0000u
void HAL_SPI_TxCpltCallback(SPI_HandleTypeDef* hspi);
void HAL_SPI_RxCpltCallback(SPI_HandleTypeDef* hspi);
void HAL_SPI_TxRxCpltCallback(SPI_HandleTypeDef* hspi);
void HAL_SPI_TxHalfCpltCallback(SPI_HandleTypeDef* hspi);
void HAL_SPI_RxHalfCpltCallback(SPI_HandleTypeDef* hspi);
void HAL_SPI_TxRxHalfCpltCallback(SPI_HandleTypeDef* hspi);
void HAL_SPI_ErrorCallback(SPI_HandleTypeDef* hspi);

typedef struct {
  uint32_t ClockSpeed, DutyCycle, OwnAddress1, AddressingMode, DualAddressMode, OwnAddress2, GeneralCallMode,
      NoStretchMode;
} I2C_InitTypeDef;
typedef struct {
  void* Instance;
  I2C_InitTypeDef Init;
} I2C_HandleTypeDef;
void HAL_I2C_MasterTxCpltCallback(I2C_HandleTypeDef* hi2c);
void HAL_I2C_MasterRxCpltCallback(I2C_HandleTypeDef* hi2c);
void HAL_I2C_MemTxCpltCallback(I2C_HandleTypeDef* hi2c);
void HAL_I2C_MemRxCpltCallback(I2C_HandleTypeDef* hi2c);
void HAL_I2C_ErrorCallback(I2C_HandleTypeDef* hi2c);

typedef struct {
  void* Instance;
} ADC_HandleTypeDef;
extern ADC_HandleTypeDef hadc1;
extern ADC_HandleTypeDef hadc2;
// stm32f4xx_ll_adc.h: ADC counts to millivolts (12-bit resolution is code 0).
#define __LL_ADC_CALC_DATA_TO_VOLTAGE(vref_mv, data, resolution) \
  ((data) * (vref_mv) / (0xFFFu >> ((resolution) >> 23u)))
HAL_StatusTypeDef HAL_ADC_Start_DMA(ADC_HandleTypeDef* hadc, uint32_t* data, uint32_t length);
void HAL_ADC_ConvCpltCallback(ADC_HandleTypeDef* hadc);

// ---- Flash: flash_helpers.cpp unlocks and clears flags around EE_WriteVariable; nothing to do.
#define FLASH_SECTOR_1 1u
#define FLASH_SECTOR_2 2u
#define FLASH_FLAG_EOP 0x01u
#define FLASH_FLAG_OPERR 0x02u
#define FLASH_FLAG_WRPERR 0x10u
#define FLASH_FLAG_PGAERR 0x20u
#define FLASH_FLAG_PGPERR 0x40u
#define FLASH_FLAG_PGSERR 0x80u
#define __HAL_FLASH_CLEAR_FLAG(flag) ((void)(flag))
#define __HAL_FLASH_DATA_CACHE_DISABLE() ((void)0)
#define __HAL_FLASH_DATA_CACHE_RESET() ((void)0)
#define __HAL_FLASH_DATA_CACHE_ENABLE() ((void)0)
HAL_StatusTypeDef HAL_FLASH_Unlock(void);
HAL_StatusTypeDef HAL_FLASH_Lock(void);

#ifdef __cplusplus
}
#endif

#endif  // SANDPAPER_LAB_STM32F4XX_HAL_H
