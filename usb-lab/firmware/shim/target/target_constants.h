/*
 * target_constants.h for the USB lab: the OpenFFBoard firmware's target configuration header,
 * shadowing Firmware/Targets/F407VG/Core/Inc/target_constants.h (found first by include order).
 *
 * It keeps the F407VG board's identity, timers and peripheral handles, and enables only what the
 * lab's 2-axis FFB joystick and 1-axis FFB wheel need. Everything not listed here is left out because it needs
 * hardware the host does not have (SPI/I2C/CAN peripherals, ADC channels as inputs, UART consoles)
 * or is a different main class. The firmware's own constants.h derives the rest from these
 * (AXIS2_FFB_HID_DESC from FFBJOYSTICK, USE_EEPROM_EMULATION from EEPROM_START_ADDRESS).
 */
#ifndef INC_TARGET_CONSTANTS_H_
#define INC_TARGET_CONSTANTS_H_

// Board identity, as the F407VG target (the product string "FFBoard F407VG" comes from HW_TYPE).
#define HW_TYPE "F407VG"
#define HW_TYPE_INT 2
#define FW_DEVID 0x413 // F407

// The F407VG target's own main.h (CubeMX pin map); its "stm32f4xx_hal.h" is the lab's HAL shim.
#include "main.h"

// Main class: the 2-axis FFB joystick (ClassIDs.h CLSID_MAIN_FFBJOY) instead of the F407VG's
// default FFBWheel (1). Written to flash at first start as cppmain.cpp does with DEFAULTMAIN.
#define DEFAULTMAIN 2
#define FFBJOYSTICK
// The second main class: the 1-axis wheel (CLSID_MAIN_FFBWHEEL, 1) with its own 1-axis HID
// descriptor (usb_hid_1ffb_desc.c; the F407VG target ships the wheel with the 2-axis one). Which of
// the two runs is the flash's current config, as on the board: OpenFFBoardFirmware::start writes it
// before the first start.
#define FFBWHEEL
#define FFBWHEEL_USE_1AXIS_DESC

// Motor drivers: the Axis chooser's RMD CAN motor slots (11 on X, 12 on Y) hold the lab's
// simulated drivers (shim/drivers/RmdMotorCAN.h). Their real header is never included.
#define RMDCAN

// Timers as on the F407VG. TIM_FFB paces FFBHIDMain::Run (HAL_TIM_Base_Start_IT, ARR in 1 us steps);
// the lab's HAL shim runs it as a steady-clock thread that calls HAL_TIM_PeriodElapsedCallback.
#define TIM_FFB htim13
#define TIM_USER htim9

// UART handles: CommandInterface.cpp always builds UART_CommandInterface's methods, which name
// external_uart; there is no UART console (UARTCOMMANDS is not defined).
extern UART_HandleTypeDef huart1;
#define UART_PORT_EXT huart1
#define UART_BUF_SIZE 1

// ADC buffers as on the F407VG: global_callbacks.cpp defines them and voltagesense.cpp reads the
// supply voltage from them. Nothing fills them in the lab (the reads are 0 V).
#define ADC1_CHANNELS 8
#define ADC2_CHANNELS 2
extern ADC_HandleTypeDef hadc2;
#define VSENSE_HADC hadc2
#define ADC_CHAN_VINT 1
#define ADC_CHAN_VEXT 0
extern volatile uint32_t ADC2_BUF[ADC2_CHANNELS];
#define VSENSE_ADC_BUF ADC2_BUF
extern volatile uint32_t ADC1_BUF[ADC1_CHANNELS];
extern ADC_HandleTypeDef hadc1;
#define AIN_HADC hadc1
#define ADC_PINS 6
#define ADC_CHAN_FPIN 0

#define BUTTON_PINS 8

// Flash: the F407VG's EEPROM emulation settings; EE_ReadVariable/EE_WriteVariable are the lab's
// in-memory map (shim/flash/eeprom_map.cpp) instead of eeprom.c on flash sectors 1 and 2.
#define USE_EEPROM_EMULATION
#define PAGE0_ID FLASH_SECTOR_1
#define PAGE1_ID FLASH_SECTOR_2
#define EEPROM_START_ADDRESS ((uint32_t)0x08004000)
#define PAGE_SIZE (uint32_t)0x4000
// Factory defaults come from the lab (shim/flash/factory_defaults.cpp), the way
// flash_helpers.cpp lets a target define them.
#define FLASH_FACTORY_DEFAULTS_OVERRIDE

#define CCRAM_SEC ".ccmram"
#define SIGBNATUREBASEADR 0

#endif /* INC_TARGET_CONSTANTS_H_ */
