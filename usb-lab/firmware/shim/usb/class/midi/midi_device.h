/*
 * TinyUSB's MIDI descriptor constants (USB Audio 1.0 and MIDI 1.0 class values), for the
 * TUD_MIDI_DESCRIPTOR template in usbd.h that usb_descriptors.cpp expands for its CDC+MIDI
 * configuration. The lab builds no MIDI main class (MIDI is not defined), so there is no MIDI API.
 */
#ifndef SANDPAPER_LAB_MIDI_DEVICE_H
#define SANDPAPER_LAB_MIDI_DEVICE_H

enum {
  AUDIO_SUBCLASS_CONTROL = 0x01,
  AUDIO_SUBCLASS_MIDI_STREAMING = 0x03,
  AUDIO_FUNC_PROTOCOL_CODE_UNDEF = 0x00,
  AUDIO_CS_AC_INTERFACE_HEADER = 0x01,
  MIDI_CS_INTERFACE_HEADER = 0x01,
  MIDI_CS_INTERFACE_IN_JACK = 0x02,
  MIDI_CS_INTERFACE_OUT_JACK = 0x03,
  MIDI_JACK_EMBEDDED = 0x01,
  MIDI_JACK_EXTERNAL = 0x02,
  MIDI_CS_ENDPOINT_GENERAL = 0x01,
};

#endif  // SANDPAPER_LAB_MIDI_DEVICE_H
