// OpenCASCADE prints its readers' and writers' messages on standard output,
// where vcpost may be writing an NC program (`-o -`): this silences its
// default messenger for a scope and gives the printers back afterwards.
// Not thread-safe (the messenger is process-wide): hold it under the lock
// that serialises the reader or writer.
#pragma once

#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_SequenceOfPrinters.hxx>

namespace vcpost::occt {

class QuietMessenger {
 public:
  QuietMessenger() : printers_(Message::DefaultMessenger()->Printers()) {
    Message::DefaultMessenger()->ChangePrinters().Clear();
  }
  ~QuietMessenger() { Message::DefaultMessenger()->ChangePrinters() = printers_; }
  QuietMessenger(const QuietMessenger&) = delete;
  QuietMessenger& operator=(const QuietMessenger&) = delete;

 private:
  Message_SequenceOfPrinters printers_;
};

}  // namespace vcpost::occt
